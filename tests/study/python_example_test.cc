// The Python reading example of docs/DATASET.md runs as printed (h5py + pandas) on a small
// dataset; skipped when the interpreter lacks h5py or pandas.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/apps/run_spall.h"
#include "tests/study/dataset_test_sweep.h"

namespace spallkit::study {
namespace {
namespace fs = std::filesystem;

// The first ```python block after the "Reading a dataset in Python" heading.
std::string DocExample() {
  std::ifstream in(std::string(SPALLKIT_SOURCE_DIR) + "/docs/DATASET.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const size_t heading = doc.find("## Reading a dataset in Python");
  const size_t start = doc.find("```python\n", heading);
  const size_t end = doc.find("```\n", start + 10);
  if (heading == std::string::npos || start == std::string::npos || end == std::string::npos)
    return "";
  return doc.substr(start + 10, end - start - 10);
}

void Replace(std::string* s, const std::string& from, const std::string& to) {
  const size_t at = s->find(from);
  ASSERT_NE(at, std::string::npos) << from;
  s->replace(at, from.size(), to);
}

TEST(PythonExampleTest, DocExampleReadsADataset) {
  if (std::system("/usr/bin/python3 -c 'import h5py, pandas' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no /usr/bin/python3 with h5py and pandas";
  std::string code = DocExample();
  ASSERT_FALSE(code.empty()) << "no python block in docs/DATASET.md";
  const fs::path dir =
      fs::temp_directory_path() / ("spall_python_example_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string sweep = WriteTinySweep(dir.string(), 1);
  const auto run =
      testing::RunSpall("dataset run " + sweep + " --out " + dir.string() + "/ds --quiet");
  ASSERT_EQ(run.code, 0) << run.err;
  // The tiny cases last 2 ms: point the example at them and skip 1 ms instead of 20.
  Replace(&code, "root = \"runs/training-set\"", "root = \"" + dir.string() + "/ds\"");
  Replace(&code, "skip_s=0.02", "skip_s=0.001");
  std::ofstream(dir / "example.py") << code;
  const std::string out_path = (dir / "out.txt").string();
  const int rc = std::system(
      ("/usr/bin/python3 -W error " + (dir / "example.py").string() + " >" + out_path + " 2>&1")
          .c_str());
  std::ifstream in(out_path);
  std::stringstream out;
  out << in.rdbuf();
  EXPECT_EQ(rc, 0) << out.str();
  EXPECT_NE(out.str().find("roller    6"), std::string::npos) << out.str();  // cases per class
  EXPECT_NE(out.str().find("case-00000 0.8 20000.0 (41,)"), std::string::npos) << out.str();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace spallkit::study

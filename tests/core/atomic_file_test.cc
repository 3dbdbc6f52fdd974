#include "core/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace fs = std::filesystem;

TEST(AtomicFile, CommitRenamesAndAbandonedWriteLeavesNothing) {
  const fs::path dir = fs::temp_directory_path() / "spallkit_atomic_test";
  fs::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  fs::remove(path);
  {
    spallkit::AtomicFile f(path);
    std::ofstream(f.temp_path()) << "partial";
    // destroyed without Commit
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir));
  spallkit::WriteFileAtomically(path, "hello");
  std::ifstream in(path);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "hello");
  fs::remove_all(dir);
}

TEST(AtomicFile, UnwritableDirectoryIsAnInputErrorNamingThePath) {
  try {
    spallkit::WriteFileAtomically("/nonexistent-dir/x.txt", "x");
    FAIL() << "expected InputError";
  } catch (const spallkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.txt"), std::string::npos);
  }
}

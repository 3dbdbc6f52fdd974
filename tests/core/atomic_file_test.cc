#include "core/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <utility>

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

// The rename would replace whatever is at the path: a symbolic link or a pipe (or a device such
// as /dev/null) is refused, naming the path and what is there; the link and its target survive.
TEST(AtomicFile, NonRegularTargetIsRefusedAndLeftAlone) {
  const fs::path dir = fs::temp_directory_path() / "spallkit_atomic_nonregular";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "target.txt";
  std::ofstream(target) << "keep";
  const fs::path link = dir / "link.txt";
  fs::create_symlink(target, link);
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const auto& [path, what] : {std::pair{link, "a symbolic link"}, std::pair{fifo, "a pipe"}}) {
    try {
      spallkit::WriteFileAtomically(path.string(), "x");
      FAIL() << "expected InputError for " << path;
    } catch (const spallkit::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string() + ": is " + what), std::string::npos)
          << e.what();
    }
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_TRUE(fs::is_fifo(fifo));
  std::ifstream in(target);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "keep");
  EXPECT_NO_THROW(spallkit::CheckReplaceableOutput(target.string()));
  EXPECT_NO_THROW(spallkit::CheckReplaceableOutput((dir / "new.txt").string()));
  fs::remove_all(dir);
}

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadslam/common/atomic_file.h"

namespace fs = std::filesystem;

namespace {
fs::path tmpDir() {
  auto d = fs::temp_directory_path() / ("roadslam_atomic_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}
std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}
}  // namespace

TEST(AtomicFile, CommitReplacesOldContentsAndLeavesNoTemp) {
  const auto d = tmpDir();
  const auto p = d / "out.txt";
  roadslam::writeFileAtomically(p.string(), "old");
  roadslam::writeFileAtomically(p.string(), "new contents");
  EXPECT_EQ(slurp(p), "new contents");
  for (auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename(), "out.txt");
  fs::remove_all(d);
}

TEST(AtomicFile, AbandonedWriteKeepsPreviousFile) {
  const auto d = tmpDir();
  const auto p = d / "out.txt";
  roadslam::writeFileAtomically(p.string(), "complete");
  {
    roadslam::AtomicFile f(p.string());
    f.stream() << "half-writ";
    // destroyed without commit(): as if the writer threw half-way
  }
  EXPECT_EQ(slurp(p), "complete");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 1);
  fs::remove_all(d);
}

TEST(AtomicFile, UnwritableFolderThrowsNamingThePath) {
  try {
    roadslam::writeFileAtomically("/nonexistent_dir_roadslam/x.txt", "x");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir_roadslam/x.txt"), std::string::npos);
  }
}

// A full disk: the temporary file is /dev/full (every write(2) fails with ENOSPC), as when the disk
// fills during a run. The error names the file and the system's reason, and nothing is left behind.
TEST(AtomicFile, FullDiskNamesTheReasonAndLeavesNoTemporaryFile) {
  const auto d = tmpDir();
  const auto p = d / "map.pcd";
  fs::create_symlink("/dev/full", roadslam::tempPathFor(p.string()));
  try {
    roadslam::AtomicFile f(p.string());
    f.stream() << std::string(200000, 'x');  // more than the buffer: write(2) runs before commit too
    f.commit();
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write '" + p.string() + "': No space left on device");
  }
  EXPECT_FALSE(fs::exists(p));
  EXPECT_TRUE(fs::is_empty(d)) << "a temporary file was left";
  fs::remove_all(d);
}

TEST(TempFile, AnUncommittedTemporaryFileIsRemoved) {
  const auto d = tmpDir();
  const auto p = d / "map.bt";
  {
    roadslam::TempFile t(p.string(), ".bt");
    std::ofstream(t.path()) << "partial";
    EXPECT_TRUE(fs::exists(t.path()));
  }
  EXPECT_TRUE(fs::is_empty(d));
  {
    roadslam::TempFile t(p.string());
    std::ofstream(t.path()) << "whole";
    t.commit();
  }
  EXPECT_EQ(slurp(p), "whole");
  fs::remove_all(d);
}

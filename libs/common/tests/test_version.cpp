// --version's text: the project version CMake was given and the commit of the source tree it was built from.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "roadslam/common/version.h"

namespace {
/// stdout of \p cmd, trailing newline removed; empty when it fails.
std::string run(const std::string& cmd) {
  std::string out;
  if (FILE* p = ::popen(cmd.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    if (::pclose(p) != 0) out.clear();
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}
}  // namespace

TEST(Version, TextNamesProgramVersionCommitAndBuildType) {
  const std::string t = roadslam::versionText("roadslam-x");
  EXPECT_EQ(t, std::string("roadslam-x ") + roadslam::projectVersion() + " (commit " + roadslam::gitCommit() + ", " +
                   roadslam::buildType() + " build)");
  EXPECT_FALSE(std::string(roadslam::projectVersion()).empty());
  EXPECT_FALSE(std::string(roadslam::buildType()).empty());
}

// The commit compiled in is the one the build recorded (its generated header as it is on disk now, not
// git's HEAD at test time: a commit or an edit after the build changes HEAD, not the binary), and it is a
// commit of the source repository (a short hash, "-dirty" when the tree had changes then), or "unknown"
// where git or the repository is absent.
TEST(Version, CommitIsTheOneTheBuildRecorded) {
  const std::string commit = roadslam::gitCommit();
  EXPECT_EQ(commit, roadslam::recordedGitCommit(ROADSLAM_BINARY_DIR)) << "this binary was linked before the build tree last recorded the commit (a partial build since): rebuild it";
  const std::string hash = commit.substr(0, commit.find("-dirty"));
  ASSERT_TRUE(commit == hash || commit == hash + "-dirty") << commit;
  if (run("git -C '" ROADSLAM_SOURCE_DIR "' rev-parse --git-dir 2>/dev/null").empty()) {
    EXPECT_EQ(commit, "unknown");
    GTEST_SKIP() << "git or the repository is absent";
  }
  ASSERT_GE(hash.size(), 7u) << commit;
  EXPECT_EQ(hash.find_first_not_of("0123456789abcdef"), std::string::npos) << commit;
  EXPECT_EQ(run("git -C '" ROADSLAM_SOURCE_DIR "' cat-file -t " + hash + " 2>/dev/null"), "commit")
      << commit << " is not a commit of " ROADSLAM_SOURCE_DIR;
}

// The recorded commit is read from the header's text (a header of another build, or none).
TEST(Version, RecordedCommitIsReadFromTheGeneratedHeader) {
  const std::string dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/version-build";
  std::filesystem::create_directories(dir + "/libs/common/generated/roadslam/common");
  std::ofstream(dir + "/libs/common/generated/roadslam/common/git_version.h")
      << "// Generated\n#pragma once\n#define ROADSLAM_GIT_COMMIT \"0a1b2c3-dirty\"\n";
  EXPECT_EQ(roadslam::recordedGitCommit(dir), "0a1b2c3-dirty");
  EXPECT_EQ(roadslam::recordedGitCommit(dir + "/nowhere"), "");
}

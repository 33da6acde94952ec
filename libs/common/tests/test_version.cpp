// --version's text: the project version CMake was given and the commit of the source tree it was built from.
#include <gtest/gtest.h>

#include <cstdio>
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

TEST(Version, CommitIsTheSourceTreesHead) {
  const std::string head = run("git -C '" ROADSLAM_SOURCE_DIR "' rev-parse --short HEAD 2>/dev/null");
  const std::string commit = roadslam::gitCommit();
  if (head.empty()) {
    EXPECT_EQ(commit, "unknown");
    GTEST_SKIP() << "git or the repository is absent";
  }
  EXPECT_TRUE(commit == head || commit == head + "-dirty") << "built from " << commit << ", HEAD is " << head;
}

#include "roadslam/common/version.h"

#include <fstream>

#include "roadslam/common/git_version.h"  // generated into the build tree by cmake/GitVersion.cmake

namespace roadslam {

const char* projectVersion() { return ROADSLAM_PROJECT_VERSION; }
const char* gitCommit() { return ROADSLAM_GIT_COMMIT; }
const char* buildType() { return ROADSLAM_BUILD_TYPE; }

std::string versionText(const std::string& program) {
  return program + " " + projectVersion() + " (commit " + gitCommit() + ", " + buildType() + " build)";
}

std::string recordedGitCommit(const std::string& build_dir) {
  std::ifstream in(build_dir + "/libs/common/generated/roadslam/common/git_version.h");
  const std::string key = "#define ROADSLAM_GIT_COMMIT \"";
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) != 0) continue;
    const auto end = line.find('"', key.size());
    return end == std::string::npos ? "" : line.substr(key.size(), end - key.size());
  }
  return "";
}

}  // namespace roadslam

#include "roadslam/common/version.h"

#include "roadslam/common/git_version.h"  // generated into the build tree by cmake/GitVersion.cmake

namespace roadslam {

const char* projectVersion() { return ROADSLAM_PROJECT_VERSION; }
const char* gitCommit() { return ROADSLAM_GIT_COMMIT; }
const char* buildType() { return ROADSLAM_BUILD_TYPE; }

std::string versionText(const std::string& program) {
  return program + " " + projectVersion() + " (commit " + gitCommit() + ", " + buildType() + " build)";
}

}  // namespace roadslam

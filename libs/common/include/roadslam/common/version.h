#pragma once
/// \file version.h
/// What `--version` prints: the program, the project version (CMake's project VERSION), the git commit
/// the binary was built from (short hash, "-dirty" when tracked files had changes, "unknown" without
/// git; refreshed at every build) and the build type.

#include <string>

namespace roadslam {

const char* projectVersion();  ///< e.g. "0.1.0"
const char* gitCommit();       ///< e.g. "bd7ab7a", "bd7ab7a-dirty" or "unknown"
const char* buildType();       ///< CMAKE_BUILD_TYPE, e.g. "Release"

/// One line: "<program> <version> (commit <hash>, <build type> build)".
std::string versionText(const std::string& program);

/// The commit the build tree \p build_dir last recorded for --version (the ROADSLAM_GIT_COMMIT of its
/// generated libs/common/generated/roadslam/common/git_version.h, as it is on disk now): what every
/// program linked in that build must report, however the source tree has moved since. "" when the
/// file is absent or holds no such line.
std::string recordedGitCommit(const std::string& build_dir);

}  // namespace roadslam

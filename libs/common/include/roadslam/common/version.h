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

}  // namespace roadslam

#pragma once
/// \file cli.h
/// Command-line conventions shared by every roadslam-* program (CLI11, header-only so the library
/// itself does not depend on CLI11): `--version`, and the stdout rules of `--quiet` / `--json`.

#include <CLI/CLI.hpp>

#include <string>

#include "roadslam/common/version.h"

namespace roadslam {

/// Adds `--version` to \p app: prints versionText(\p program) on stdout and exits 0.
inline void addVersionFlag(CLI::App& app, const std::string& program) {
  app.set_version_flag("--version", versionText(program), "print the version, git commit and build type, and exit");
}

}  // namespace roadslam

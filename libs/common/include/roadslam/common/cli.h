#pragma once
/// \file cli.h
/// Command-line conventions shared by every roadslam-* program (CLI11, header-only so the library
/// itself does not depend on CLI11): `--version`, and the stdout rules of `--quiet` / `--json`.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "roadslam/common/version.h"

namespace roadslam {

/// Adds `--version` to \p app: prints versionText(\p program) on stdout and exits 0.
inline void addVersionFlag(CLI::App& app, const std::string& program) {
  app.set_version_flag("--version", versionText(program), "print the version, git commit and build type, and exit");
}

/// Exit code of a run a stop signal ended (128 + SIGINT, as a shell reports it).
constexpr int kInterruptedExit = 130;

/// The one way every program ends after Ctrl-C / SIGTERM: its outputs so far written, one line on
/// stderr saying so ("PROGRAM: interrupted: WHAT"), exit kInterruptedExit.
inline int interruptedExit(const std::string& program, const std::string& what) {
  std::fprintf(stderr, "%s: interrupted: %s\n", program.c_str(), what.c_str());
  return kInterruptedExit;
}

/// Adds `--force` (write into a folder that holds another program's or another input's run,
/// runfolder/output_folder.h) to \p app.
inline void addForceFlag(CLI::App& app, bool& force) {
  app.add_flag("--force", force, "write into --out even when it holds another program's or another input's files");
}

}  // namespace roadslam

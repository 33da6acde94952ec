#pragma once
/// \file cli.h
/// Command-line conventions shared by every roadslam-* program (CLI11, header-only so the library
/// itself does not depend on CLI11): `--version`, and the stdout rules of `--quiet` / `--json`.

#include <CLI/CLI.hpp>

#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>

#include "roadslam/common/version.h"

namespace roadslam {

/// Adds `--version` to \p app: prints versionText(\p program) on stdout and exits 0.
inline void addVersionFlag(CLI::App& app, const std::string& program) {
  app.set_version_flag("--version", versionText(program), "print the version, git commit and build type, and exit");
}

/// The old spellings of options (docs/cli.md "One convention"): CLI11 accepts them as other names of
/// the same option; this says on stderr, once each, what to write instead. Call before parsing.
inline void warnOldSpellings(int argc, char** argv, const std::string& program,
                             std::initializer_list<std::pair<const char*, const char*>> old_to_new) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    for (const auto& [old_name, new_name] : old_to_new) {
      const std::string o = old_name;
      if (arg == o || arg.rfind(o + "=", 0) == 0)
        std::fprintf(stderr, "%s: %s is an old spelling: use %s\n", program.c_str(), old_name, new_name);
    }
  }
}

/// Adds `--allow-unknown-keys` to \p app.
inline void addAllowUnknownKeysFlag(CLI::App& app, bool& allow) {
  app.add_flag("--allow-unknown-keys", allow, "ini keys no component reads are warnings, not errors");
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

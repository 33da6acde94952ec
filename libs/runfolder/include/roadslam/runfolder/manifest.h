#pragma once
/// \file manifest.h
/// run.json, the manifest of a run folder: which format and version the folder's files follow, which
/// program wrote it and from which input (docs/run-folder.md). Written last by the writers, so a folder
/// with a manifest has all its files; checked first by the readers, so an older or foreign folder fails
/// naming the file instead of being misread.

#include <optional>
#include <string>

namespace roadslam::runfolder {

constexpr const char* kManifestFile = "run.json";
constexpr const char* kFormat = "roadslam-run";  ///< run.json "format"
constexpr int kFormatVersion = 1;                ///< run.json "format_version": the one this build writes and reads
constexpr const char* kMapProgram = "roadslam-map";
constexpr const char* kBoundsProgram = "roadslam-bounds";

struct Manifest {
  std::string format = kFormat;
  int format_version = kFormatVersion;
  std::string program;          ///< the writer: kMapProgram, kBoundsProgram
  std::string program_version;  ///< its versionText(), e.g. "roadslam-map 0.1.0 (commit bd7ab7a, Release build)"
  std::string input;            ///< what the run read (the source's describe())
  /// The main input's identity (output_folder.h compares it): its absolute canonical path, with what
  /// else makes the run's data (the simulator: "?seed=N&duration_s=D"); empty in folders written
  /// before it was recorded.
  std::string input_id;
  /// "complete": every file written (the writers' last step); "writing": claimed by a run that has not
  /// finished (running, or killed: its files may be missing or from an earlier run).
  std::string state = "complete";
};

/// Writes \p dir/run.json atomically (program_version filled in when empty); throws naming the file.
void writeManifest(const std::string& dir, Manifest m);

/// Reads \p dir/run.json and checks it: format kFormat, format_version kFormatVersion, state
/// "complete" and, when \p program is not empty, written by \p program. Throws std::runtime_error naming the file: absent
/// (a folder written before run.json existed, or not a run folder: the message names the program that
/// re-creates it), unreadable, another format, another version, another program.
Manifest readManifest(const std::string& dir, const std::string& program);

/// run.json of \p dir as it is, unchecked (std::nullopt when absent or unreadable): what wrote the folder.
std::optional<Manifest> peekManifest(const std::string& dir);

}  // namespace roadslam::runfolder

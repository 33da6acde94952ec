#pragma once
/// \file output_folder.h
/// Who may write into an output folder (docs/run-folder.md, "Whose folder it is"). A run claims its
/// `--out` folder before it writes anything: the folder must be new or empty, or hold a run of the
/// same program on the same input (a re-run replaces it), and must not be or hold one of the run's own
/// inputs. Anything else (another program's folder, another drive's run, a data folder, the prior map)
/// is refused naming what is there, unless the user says `--force`. The claim writes run.json with
/// state "writing"; the run's last step writes it "complete" (manifest.h).

#include <stdexcept>
#include <string>
#include <vector>

namespace roadslam::runfolder {

struct OutputClaim {
  std::string program;              ///< the writer: kMapProgram, kBoundsProgram, "roadslam-sim", ...
  std::string input;                ///< the main input as given (its canonical path is the run's identity)
  std::string input_description;    ///< what run.json "input" says (default: input)
  std::string input_suffix;         ///< appended to the canonical input in input_id (the simulator's "?seed=1&duration_s=60")
  std::vector<std::string> reads;   ///< the run's other inputs (config, prior map, side inputs): never written over
  bool force = false;               ///< write anyway (the refusal is then a warning)
};

/// A folder a run may not write into; the message says what is there and what to do.
struct OutputRefused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The canonical absolute form of \p path (weakly_canonical: \p path may not exist yet).
std::string canonicalPath(const std::string& path);

/// run.json "input_id" of \p claim: canonicalPath(input) + input_suffix.
std::string inputId(const OutputClaim& claim);

/// Why \p dir may not take \p claim's outputs; empty when it may.
std::string refusalReason(const std::string& dir, const OutputClaim& claim);

/// Checks \p dir (refusalReason; throws OutputRefused unless claim.force), creates it when missing
/// and writes its run.json with state "writing". Returns the warnings of a forced claim (empty
/// otherwise). Throws std::runtime_error naming the folder and the reason when it cannot be created
/// or written.
std::vector<std::string> claimOutputFolder(const std::string& dir, const OutputClaim& claim);

}  // namespace roadslam::runfolder

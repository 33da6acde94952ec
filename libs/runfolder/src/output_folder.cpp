#include "roadslam/runfolder/output_folder.h"

#include <filesystem>

#include "roadslam/runfolder/manifest.h"

namespace fs = std::filesystem;

namespace roadslam::runfolder {
namespace {

/// \p path is \p dir or lies inside it (both canonical).
bool within(const std::string& path, const std::string& dir) {
  if (path == dir) return true;
  const std::string prefix = dir.back() == '/' ? dir : dir + "/";
  return path.compare(0, prefix.size(), prefix) == 0;
}

/// A few names of what \p dir holds, for the message.
std::string someEntries(const std::string& dir) {
  std::string names;
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (n++ == 3) return names + ", ...";
    names += (names.empty() ? "" : ", ") + e.path().filename().string();
  }
  return names;
}

const char* kWhatToDo = "; give a new or empty --out folder, or --force to write there anyway";

}  // namespace

std::string canonicalPath(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  return (ec ? fs::absolute(path).lexically_normal() : p).string();
}

std::string inputId(const OutputClaim& claim) {
  return (claim.input.empty() ? "" : canonicalPath(claim.input)) + claim.input_suffix;
}

std::string refusalReason(const std::string& dir, const OutputClaim& claim) {
  const std::string out = canonicalPath(dir);
  std::vector<std::string> inputs = claim.reads;
  if (!claim.input.empty()) inputs.insert(inputs.begin(), claim.input);
  for (const auto& in : inputs) {
    if (!in.empty() && within(canonicalPath(in), out)) {
      return "'" + dir + "' is or holds this run's input '" + in + "': its outputs would overwrite what it reads" + kWhatToDo;
    }
  }
  std::error_code ec;
  if (!fs::exists(dir, ec)) return "";
  if (!fs::is_directory(dir, ec)) return "'" + dir + "' is a file, not a folder";
  if (fs::is_empty(dir, ec)) return "";
  const auto m = peekManifest(dir);
  if (!m) {
    return "'" + dir + "' holds files no roadslam run wrote (" + someEntries(dir) + "; no " + kManifestFile + ")" + kWhatToDo;
  }
  if (m->program != claim.program) {
    return "'" + dir + "' holds the outputs of " + m->program + " (its " + kManifestFile + "), not of " + claim.program + kWhatToDo;
  }
  const std::string identity = inputId(claim);
  if (!m->input_id.empty() && m->input_id != identity) {  // empty: a run from before input_id, of this program
    return "'" + dir + "' holds " + m->program + "'s run on " + (m->input_id.empty() ? "'" + m->input + "'" : m->input_id) +
           ", not on " + identity + kWhatToDo;
  }
  return "";
}

std::vector<std::string> claimOutputFolder(const std::string& dir, const OutputClaim& claim) {
  std::vector<std::string> warnings;
  const std::string why = refusalReason(dir, claim);
  if (!why.empty() && !claim.force) throw OutputRefused(why);
  if (!why.empty()) warnings.push_back("--force: " + why.substr(0, why.find(kWhatToDo)));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw std::runtime_error("cannot create output folder '" + dir + "': " + ec.message());
  Manifest m;
  m.program = claim.program;
  m.input = claim.input_description.empty() ? claim.input : claim.input_description;
  m.input_id = inputId(claim);
  m.state = "writing";
  writeManifest(dir, m);  // also the probe that the folder is writable, before hours of processing
  return warnings;
}

}  // namespace roadslam::runfolder

#include "roadslam/runfolder/manifest.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/version.h"

namespace roadslam::runfolder {

void writeManifest(const std::string& dir, Manifest m) {
  if (m.program_version.empty()) m.program_version = versionText(m.program);
  const nlohmann::json j = {{"format", m.format},   {"format_version", m.format_version}, {"program", m.program},
                            {"program_version", m.program_version}, {"input", m.input},
                            {"input_id", m.input_id}, {"state", m.state}};
  writeFileAtomically(dir + "/" + kManifestFile, j.dump(2) + "\n");
}

namespace {
Manifest fromJson(const nlohmann::json& j) {
  Manifest m;
  m.format = j.at("format").get<std::string>();
  m.format_version = j.at("format_version").get<int>();
  m.program = j.value("program", "");
  m.program_version = j.value("program_version", "");
  m.input = j.value("input", "");
  m.input_id = j.value("input_id", "");
  m.state = j.value("state", "complete");
  return m;
}
}  // namespace

std::optional<Manifest> peekManifest(const std::string& dir) {
  std::ifstream in(dir + "/" + kManifestFile);
  if (!in) return std::nullopt;
  try {
    return fromJson(nlohmann::json::parse(in));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

Manifest readManifest(const std::string& dir, const std::string& program) {
  const std::string path = dir + "/" + kManifestFile;
  const std::string remake = program.empty() ? std::string("the program that wrote it") : program;
  if (!std::filesystem::is_directory(dir)) throw std::runtime_error(dir + ": not a folder (a " + remake + " output folder is wanted)");
  std::ifstream in(path);
  if (!in) {
    throw std::runtime_error(path + ": missing: not a run folder, or one written before run folders had a manifest; "
                             "re-create it with " + remake);
  }
  Manifest m;
  try {
    m = fromJson(nlohmann::json::parse(in));
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not a run manifest: " + e.what());
  }
  if (m.format != kFormat) throw std::runtime_error(path + ": format '" + m.format + "', not '" + kFormat + "'");
  if (m.format_version != kFormatVersion) {
    throw std::runtime_error(path + ": format_version " + std::to_string(m.format_version) + ", this build reads " +
                             std::to_string(kFormatVersion) + "; re-create the folder with this build's " + remake);
  }
  if (!program.empty() && m.program != program) {
    throw std::runtime_error(path + ": written by '" + m.program + "', not by " + program);
  }
  if (m.state != "complete") {
    throw std::runtime_error(path + ": state '" + m.state + "': the " + m.program +
                             " run writing this folder has not finished (still running, or killed); run it again");
  }
  return m;
}

}  // namespace roadslam::runfolder

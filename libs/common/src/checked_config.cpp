#include "roadslam/common/checked_config.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace roadslam {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

/// The candidate nearest to \p word, or "" when none is within half the word's length.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_d = word.size() / 2 + 1;
  for (const auto& c : candidates) {
    const size_t d = editDistance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

}  // namespace

const std::vector<std::string>& knownSections() {
  static const std::vector<std::string> s = {
      "velodyne", "preprocess", "kitti", "registration", "odometry", "mapping", "pose_graph", "loop_closure",
      "loop_closure_coarse", "loop_closure_fine", "loop_closure_place", "loop_closure_global", "loop_closure_global_fine",
      "localization", "localization_track", "point_map", "octomap", "grid", "vehicle_prior", "ground",
      "boundary", "objects", "tracking", "seen_through", "gnss_fusion", "scenario", "world", "trajectory", "lidar", "can", "gnss",
      "grab", "vehicle"};
  return s;
}

size_t editDistance(const std::string& a0, const std::string& b0) {
  // optimal string alignment: a swap of two neighbours (heigth / height) is one edit
  const std::string a = lower(a0), b = lower(b0);
  std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
  for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    for (size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

CheckedConfig::CheckedConfig(const std::string& path) : path_(path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open config file '" + path + "'");
  {  // an ini is text: a NUL byte in its head means a capture, a rawlog or a map was given instead
    char head[4096];
    in.read(head, sizeof head);
    if (std::memchr(head, '\0', static_cast<size_t>(in.gcount())))
      throw std::runtime_error("config file '" + path + "' is a binary file, not an ini");
    in.clear();
    in.seekg(0);
  }
  file_.setFileName(path);
  std::string line, section;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::string t = trim(line);
    if (t.empty() || t[0] == ';' || t[0] == '#') continue;
    if (t[0] == '[') {
      section = lower(trim(t.substr(1, t.find(']') - 1)));
      section_lines_.emplace(section, n);
      continue;
    }
    const auto eq = t.find('=');
    if (eq != std::string::npos) key_lines_.emplace(std::make_pair(section, lower(trim(t.substr(0, eq)))), n);
  }
  // Every roadslam ini is made of sections: one without any would leave every component on its
  // built-in defaults without a word.
  if (section_lines_.empty())
    throw std::runtime_error("config file '" + path + "' has no [section]: not a roadslam ini (every shipped one is in ini/)");
}

void CheckedConfig::writeString(const std::string& section, const std::string& name, const std::string& str) {
  file_.write(section, name, str);
}

std::string CheckedConfig::readString(const std::string& section, const std::string& name,
                                      const std::string& defaultStr, bool failIfNotFound) const {
  read_.emplace(lower(section), lower(name));
  return file_.read_string(section, name, defaultStr, failIfNotFound);
}

std::vector<std::string> CheckedConfig::unknownEntries() const {
  std::set<std::string> read_sections;
  for (const auto& [s, k] : read_) read_sections.insert(s);
  std::vector<std::string> all_known(knownSections().begin(), knownSections().end());
  all_known.insert(all_known.end(), read_sections.begin(), read_sections.end());
  std::vector<std::pair<int, std::string>> out;
  for (const auto& [sec, line] : section_lines_) {
    if (read_sections.count(sec) ||
        std::find(knownSections().begin(), knownSections().end(), sec) != knownSections().end()) {
      continue;
    }
    const std::string near = nearest(sec, all_known);
    out.emplace_back(line, path_ + ":" + std::to_string(line) + ": unknown section [" + sec + "]" +
                               (near.empty() ? "" : " (nearest known: [" + near + "])"));
  }
  for (const auto& [sk, line] : key_lines_) {
    const auto& [sec, key] = sk;
    if (!read_sections.count(sec) || read_.count(sk)) continue;  // another program's section, or read
    std::vector<std::string> keys;
    for (const auto& [s, k] : read_) {
      if (s == sec) keys.push_back(k);
    }
    const std::string near = nearest(key, keys);
    out.emplace_back(line, path_ + ":" + std::to_string(line) + ": unknown key '" + key + "' in [" + sec + "]" +
                               (near.empty() ? "" : " (nearest known: " + near + ")"));
  }
  std::sort(out.begin(), out.end());
  std::vector<std::string> lines;
  for (auto& [n, s] : out) lines.push_back(std::move(s));
  return lines;
}

int CheckedConfig::lineOf(const std::string& section, const std::string& key) const {
  const auto it = key_lines_.find({lower(section), lower(key)});
  return it == key_lines_.end() ? 0 : it->second;
}

std::string nearestName(const std::string& word, const std::vector<std::string>& candidates) {
  return nearest(word, candidates);
}

std::vector<std::string> CheckedConfig::checkEntries(bool allow) const {
  auto bad = unknownEntries();
  if (bad.empty() || allow) return bad;
  std::string msg;
  for (const auto& b : bad) msg += (msg.empty() ? "" : "\n") + b;
  throw std::runtime_error(msg + "\n(a typo leaves the default in force; --allow-unknown-keys accepts them)");
}

}  // namespace roadslam

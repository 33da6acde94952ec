#pragma once
/// \file checked_config.h
/// An ini file that remembers which keys the program asked for, so a key nobody reads (a typo:
/// `voxel_sise_m`, `[odometri]`) is reported instead of silently leaving a default in force. Every
/// component reads its section through the usual helpers (config.h); once a job has loaded all of
/// them it calls unknownEntries() / throwOnUnknownEntries(). One mechanism for every app: nothing
/// lists keys twice, the components' own reads are the list.

#include <mrpt/config/CConfigFile.h>

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace roadslam {

/// Sections some roadslam program reads from its inis. A section of this list that the running
/// program did not read is another program's (ini/default.ini serves roadslam-map and
/// roadslam-bounds alike), so it is not reported; a section outside it is.
const std::vector<std::string>& knownSections();

/// Edit distance between \p a and \p b, case-insensitive: insertions, deletions, substitutions and
/// swaps of neighbours (optimal string alignment).
size_t editDistance(const std::string& a, const std::string& b);
/// The candidate nearest to \p word, or "" when none is within half its length.
std::string nearestName(const std::string& word, const std::vector<std::string>& candidates);

class CheckedConfig : public mrpt::config::CConfigFileBase {
 public:
  /// Opens \p path; throws std::runtime_error naming it when it cannot be read.
  explicit CheckedConfig(const std::string& path);

  const std::string& path() const { return path_; }
  void getAllSections(std::vector<std::string>& sections) const override { file_.getAllSections(sections); }
  void getAllKeys(const std::string& section, std::vector<std::string>& keys) const override {
    file_.getAllKeys(section, keys);
  }
  void clear() override { file_.clear(); }

  /// One line per key of the file that no component read, in file order:
  /// "FILE:LINE: unknown key 'voxel_sise_m' in [odometry] (nearest known: voxel_size_m)" and
  /// "FILE:LINE: unknown section [odometri] (nearest known: [odometry])".
  std::vector<std::string> unknownEntries() const;
  /// Throws std::runtime_error listing unknownEntries() unless there are none or \p allow, in which
  /// case they are returned as warnings.
  std::vector<std::string> checkEntries(bool allow) const;
  /// 1-based line of \p key in \p section, 0 when the file has no such key.
  int lineOf(const std::string& section, const std::string& key) const;

 protected:
  void writeString(const std::string& section, const std::string& name, const std::string& str) override;
  std::string readString(const std::string& section, const std::string& name, const std::string& defaultStr,
                         bool failIfNotFound = false) const override;

 private:
  std::string path_;
  mrpt::config::CConfigFile file_;
  mutable std::set<std::pair<std::string, std::string>> read_;  ///< (section, key), lower case
  std::map<std::pair<std::string, std::string>, int> key_lines_;  ///< lower case -> 1-based line
  std::map<std::string, int> section_lines_;
};

}  // namespace roadslam

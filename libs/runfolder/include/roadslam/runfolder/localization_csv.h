#pragma once
/// \file localization_csv.h
/// localization.csv of `roadslam-map --prior-map`: one row per sweep, how it was placed in the prior
/// map (docs/run-folder.md).

#include <string>
#include <vector>

namespace roadslam::runfolder {

constexpr const char* kLocalizationCsv = "localization.csv";

struct LocalizationRow {
  size_t frame = 0;        ///< frames.csv index [-]
  double stamp_s = 0;      ///< [s]
  std::string status;      ///< localization::toString(LocalizationStatus): tracked, relocalized, lost
  double confidence = 0;   ///< overlap of the final alignment [0, 1]
  size_t keyframe = 0;     ///< relocalized: the prior map's keyframe it was found at [-]
  int weak_directions = 0; ///< [-]
  std::string reason;      ///< lost: why (commas written as ';')
};

std::string localizationCsvHeader();            ///< with its newline
std::string localizationCsvRow(const LocalizationRow& r);  ///< with its newline
void writeLocalizationCsv(const std::string& path, const std::vector<LocalizationRow>& rows);
/// By column name; throws naming the file and the column or line.
std::vector<LocalizationRow> readLocalizationCsv(const std::string& path);

}  // namespace roadslam::runfolder

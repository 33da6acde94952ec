#include "roadslam/runfolder/localization_csv.h"

#include "roadslam/common/atomic_file.h"
#include "roadslam/runfolder/csv.h"

namespace roadslam::runfolder {

std::string localizationCsvHeader() { return "frame,stamp_s,status,confidence,keyframe,weak_directions,reason\n"; }

std::string localizationCsvRow(const LocalizationRow& r) {
  return format("%zu,%f,%s,%f,%zu,%d,", r.frame, r.stamp_s, r.status.c_str(), r.confidence, r.keyframe,
                r.weak_directions) +
         csvText(r.reason) + "\n";
}

void writeLocalizationCsv(const std::string& path, const std::vector<LocalizationRow>& rows) {
  std::string out = localizationCsvHeader();
  for (const auto& r : rows) out += localizationCsvRow(r);
  writeFileAtomically(path, out);
}

std::vector<LocalizationRow> readLocalizationCsv(const std::string& path) {
  std::vector<LocalizationRow> rows;
  for (CsvReader c(path, {"frame", "stamp_s", "status", "confidence", "keyframe", "weak_directions", "reason"}); c.next();) {
    LocalizationRow r;
    r.frame = static_cast<size_t>(c.integer("frame"));
    r.stamp_s = c.number("stamp_s");
    r.status = c.text("status");
    r.confidence = c.number("confidence");
    r.keyframe = static_cast<size_t>(c.integer("keyframe"));
    r.weak_directions = static_cast<int>(c.integer("weak_directions"));
    r.reason = c.text("reason");
    rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace roadslam::runfolder

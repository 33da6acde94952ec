// buildReport: the sensors, the CAN log and the map folder read into one RecordingReport; its JSON and
// text forms, and the report folder.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "internal.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/runfolder/manifest.h"
#include "roadslam/runfolder/output_folder.h"

namespace roadslam::recording_report {

namespace {

/// A CAN log recorded at another time than the sensors is most likely the wrong file: said, not refused.
void checkOverlap(RecordingReport& r, const std::vector<PendingStream>& pending) {
  double s0 = 1e300, s1 = -1e300, c0 = 1e300, c1 = -1e300;
  for (const auto& ps : pending) {
    if (ps.stamps.empty()) continue;
    const auto [lo, hi] = std::minmax_element(ps.stamps.begin(), ps.stamps.end());
    double& a = ps.info.kind == "can" ? c0 : s0;
    double& b = ps.info.kind == "can" ? c1 : s1;
    a = std::min(a, *lo), b = std::max(b, *hi);
  }
  if (c1 < c0 || s1 < s0 || (c0 <= s1 && s0 <= c1)) return;
  char b[256];
  std::snprintf(b, sizeof b, "the CAN log does not overlap the recording in time (it starts %.1f s %s it)",
                c0 > s1 ? c0 - s1 : s0 - c1, c0 > s1 ? "after the end of" : "before the start of");
  r.warnings.push_back(b);
}

}  // namespace

RecordingReport buildReport(const ReportInputs& in, const ReportParams& p) {
  RecordingReport r;
  r.recording = in.recording;
  if (!std::filesystem::exists(in.recording)) throw std::runtime_error(in.recording + ": no such file or folder");
  r.files = recordingFiles(in.recording);
  std::vector<PendingStream> pending = readSensors(r, in.lidar_model);
  const std::vector<std::string> logs = in.can_log.empty() ? canSidecars(in.recording) : std::vector{in.can_log};
  if (!logs.empty()) r.can = readCan(logs, in.vehicle_ini, p, pending);
  if (!in.map_dir.empty()) r.map = readMap(in.map_dir, p);
  r.start_s = std::numeric_limits<double>::infinity();
  r.end_s = -r.start_s;
  for (const auto& ps : pending) {
    if (ps.stamps.empty()) continue;
    r.start_s = std::min(r.start_s, *std::min_element(ps.stamps.begin(), ps.stamps.end()));
    r.end_s = std::max(r.end_s, *std::max_element(ps.stamps.begin(), ps.stamps.end()));
  }
  checkOverlap(r, pending);
  for (auto& ps : pending) {
    StreamStats s = streamStats(std::move(ps.stamps), ps.nominal_period_s, r.start_s, p);
    const StreamStats& i = ps.info;
    s.label = i.label, s.kind = i.kind, s.drops = i.drops, s.malformed = i.malformed, s.model = i.model;
    s.model_source = i.model_source;
    s.sweeps = i.sweeps, s.sweep_rate_hz = i.sweep_rate_hz;
    r.streams.push_back(std::move(s));
  }
  if (r.can) shiftCanTimes(*r.can, r.start_s);
  for (double& t : r.gnss_t_s) t -= r.start_s;
  r.gnss_t_s = decimate(r.gnss_t_s, p.max_plot_points);
  r.gnss_x_m = decimate(r.gnss_x_m, p.max_plot_points);
  r.gnss_y_m = decimate(r.gnss_y_m, p.max_plot_points);
  return r;
}

namespace {

nlohmann::json streamJson(const StreamStats& s, double start_s) {
  nlohmann::json gaps = nlohmann::json::array();
  for (const auto& g : s.gaps)
    gaps.push_back({{"start_s", g.start_s - start_s}, {"end_s", g.end_s - start_s}, {"length_s", g.length()}});
  nlohmann::json j = {{"label", s.label}, {"kind", s.kind}, {"count", s.count}, {"first_s", s.first_s - start_s},
                      {"last_s", s.last_s - start_s}, {"rate_hz", s.rate_hz}, {"nominal_period_s", s.nominal_period_s},
                      {"gap_threshold_s", s.gap_threshold_s}, {"gap_count", s.gap_count}, {"gap_time_s", s.gap_time_s},
                      {"gaps", gaps}, {"drops", s.drops}, {"malformed", s.malformed},
                      {"rate_over_time", {{"bin_start_s", s.bin_t_s}, {"rate_hz", s.bin_rate_hz}}}};
  if (s.kind == "lidar")
    j["model"] = s.model, j["model_source"] = s.model_source, j["sweeps"] = s.sweeps, j["sweep_rate_hz"] = s.sweep_rate_hz;
  return j;
}

}  // namespace

nlohmann::json toJson(const RecordingReport& r) {
  nlohmann::json j = {{"recording", r.recording}, {"files", r.files}, {"format", r.format},
                      {"damage", r.damage}, {"warnings", r.warnings},       {"start_s", r.start_s}, {"duration_s", r.end_s - r.start_s},
                      {"other_records", r.sensor_records}};
  j["note"] = "times are seconds since start_s (Unix epoch seconds) unless named otherwise";
  j["streams"] = nlohmann::json::array();
  for (const auto& s : r.streams) j["streams"].push_back(streamJson(s, r.start_s));
  j["gnss"] = {{"fixes", r.gnss_fixes}, {"length_m", r.gnss_length_m}, {"t_s", r.gnss_t_s}, {"x_m", r.gnss_x_m},
               {"y_m", r.gnss_y_m}};
  if (r.can) {
    const CanReport& c = *r.can;
    nlohmann::json ids = nlohmann::json::array();
    for (const auto& i : c.ids)
      ids.push_back({{"iface", i.iface}, {"id", i.id}, {"extended", i.extended}, {"name", i.name}, {"count", i.count},
                     {"rate_hz", i.rate_hz}, {"median_period_s", i.median_period_s},
                     {"max_period_s", i.max_period_s}, {"gaps", i.gaps}});
    nlohmann::json sig = nlohmann::json::object();
    for (const auto& s : c.signals)
      sig[s.name] = {{"unit", s.unit}, {"min", s.min}, {"max", s.max}, {"mean", s.mean}, {"t_s", s.t_s}, {"value", s.value}};
    j["can"] = {{"log", c.log}, {"lines", c.lines}, {"frames", c.frames}, {"bad_lines", c.bad_lines},
                {"issues", c.issues}, {"ids", ids}, {"vehicle", c.vehicle}, {"signals", sig},
                {"dead_reckoning", {{"length_m", c.path_length_m}, {"gap_time_s", c.dead_reckoning_gap_time_s},
                                    {"x_m", c.path_x_m}, {"y_m", c.path_y_m}}}};
  }
  if (r.map) {
    const MapReport& m = *r.map;
    j["map"] = {{"dir", m.dir}, {"poses", m.poses}, {"length_m", m.length_m}, {"pictures", m.pictures},
                {"summary", m.summary}, {"x_m", m.x_m}, {"y_m", m.y_m}};
  }
  return j;
}

std::string toText(const RecordingReport& r) {
  char b[512];
  std::string t;
  std::snprintf(b, sizeof b, "%s: %s, %.1f s, %zu streams\n", r.recording.c_str(), r.format.c_str(),
                r.end_s - r.start_s, r.streams.size());
  t += b;
  for (const auto& s : r.streams) {
    std::snprintf(b, sizeof b, "  %-40s %9llu  %8.2f Hz  gaps %llu (%.2f s)  drops %llu", s.label.c_str(),
                  static_cast<unsigned long long>(s.count), s.rate_hz, static_cast<unsigned long long>(s.gap_count),
                  s.gap_time_s, static_cast<unsigned long long>(s.drops));
    t += b;
    if (s.kind == "lidar") {
      std::snprintf(b, sizeof b, "  sweeps %llu at %.2f Hz", static_cast<unsigned long long>(s.sweeps), s.sweep_rate_hz);
      t += b;
    }
    t += "\n";
  }
  if (r.gnss_fixes > 0) {
    std::snprintf(b, sizeof b, "  GNSS: %llu fixes, %.1f m\n", static_cast<unsigned long long>(r.gnss_fixes), r.gnss_length_m);
    t += b;
  }
  if (r.can) {
    std::snprintf(b, sizeof b, "  CAN: %llu frames, %llu bad lines, %zu ids", static_cast<unsigned long long>(r.can->frames),
                  static_cast<unsigned long long>(r.can->bad_lines), r.can->ids.size());
    t += b;
    if (!r.can->vehicle.empty()) {
      std::snprintf(b, sizeof b, ", dead-reckoned path %.1f m", r.can->path_length_m);
      t += b;
    }
    t += "\n";
  }
  if (r.map) {
    std::snprintf(b, sizeof b, "  map: %llu poses, %.1f m\n", static_cast<unsigned long long>(r.map->poses), r.map->length_m);
    t += b;
  }
  for (const auto& w : r.warnings) t += "  warning: " + w + "\n";
  if (!r.damage.empty()) t += "  damaged: " + r.damage + " (reported up to there)\n";
  return t;
}

namespace {
constexpr const char* kReportProgram = "roadslam-report";

runfolder::OutputClaim reportClaim(const ReportInputs& in, bool force) {
  return {kReportProgram, in.recording, "", "", {in.can_log, in.vehicle_ini, in.map_dir}, force};
}
}  // namespace

std::string reportFolderRefusal(const std::string& dir, const ReportInputs& in) {
  return runfolder::refusalReason(dir, reportClaim(in, false));
}

std::vector<std::string> claimReportFolder(const std::string& dir, const ReportInputs& in, bool force) {
  return runfolder::claimOutputFolder(dir, reportClaim(in, force));
}

void writeReport(const RecordingReport& r, const std::string& dir) {
  std::filesystem::create_directories(dir);
  writeFileAtomically(dir + "/report.json", toJson(r).dump(1) + "\n");
  writeFileAtomically(dir + "/report.html", toHtml(r));
  if (auto m = runfolder::peekManifest(dir); m && m->program == kReportProgram) {
    m->state = "complete";  // the claim's run.json, now with every file (docs/run-folder.md)
    runfolder::writeManifest(dir, *m);
  }
}

}  // namespace roadslam::recording_report

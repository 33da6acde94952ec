// report.html: the RecordingReport as one self-contained page (libs/report).
#include <cstdio>
#include <ctime>

#include "internal.h"
#include "roadslam/report/html_page.h"
#include "roadslam/report/svg_plot.h"

namespace roadslam::recording_report {
namespace {

using report::PlotOptions;
using report::Series;

std::string f(double v, int prec = 2) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*f", prec, v);
  return b;
}
std::string n(std::uint64_t v) { return std::to_string(v); }

std::string utc(double t_s) {
  const auto t = static_cast<std::time_t>(t_s);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char b[64];
  std::strftime(b, sizeof b, "%Y-%m-%d %H:%M:%S UTC", &tm);
  return b;
}

void sensorSection(report::HtmlPage& page, const RecordingReport& r) {
  page.heading("Sensors");
  std::vector<std::vector<std::string>> rows;
  for (const auto& s : r.streams) {
    rows.push_back({s.label, s.kind == "lidar" ? s.model : s.kind, f(s.first_s - r.start_s), f(s.last_s - r.start_s),
                    n(s.count), f(s.rate_hz), f(s.nominal_period_s * 1e3, 3), n(s.gap_count), f(s.gap_time_s, 3),
                    s.kind == "lidar" ? n(s.drops) : "", s.kind == "lidar" ? n(s.sweeps) : "",
                    s.kind == "lidar" ? f(s.sweep_rate_hz) : ""});
  }
  page.table({"sensor", "kind", "first [s]", "last [s]", "messages", "mean rate [Hz]", "nominal period [ms]", "gaps",
              "gap time [s]", "drops (sensor clock)", "sweeps", "sweep rate [Hz]"},
             rows);
  page.paragraph("Times in seconds since the start of the recording (" + utc(r.start_s) +
                 "). A gap is an interval longer than the gap factor times the nominal period (the sensor's packet "
                 "period for a Velodyne, else the median interval), and never shorter than the minimum gap.");
  std::vector<std::vector<std::string>> gap_rows;
  for (const auto& s : r.streams) {
    for (const auto& g : s.gaps)
      gap_rows.push_back({s.label, f(g.start_s - r.start_s, 3), f(g.end_s - r.start_s, 3), f(g.length(), 3)});
  }
  if (!gap_rows.empty()) {
    page.heading("Gaps", 3);
    page.table({"sensor", "from [s]", "to [s]", "length [s]"}, gap_rows);
  }
  for (const char* kind : {"lidar", "gps", "rawlog", "can"}) {
    std::vector<Series> series;
    PlotOptions o;
    const std::string k = kind;
    o.title = (k == "lidar" ? "LiDAR data packets" : k == "gps" ? "GPS / position" : k == "rawlog" ? "other rawlog records" : "CAN frames") +
              std::string(" per second (gaps dashed)");
    o.x_label = "time since start [s]";
    o.y_label = "rate [Hz]";
    o.points = false;
    o.y_include_zero = true;  // a drop to zero is a drop
    for (const auto& s : r.streams) {
      if (s.kind != kind) continue;
      series.push_back({s.label, s.bin_t_s, s.bin_rate_hz});
      for (const auto& g : s.gaps) o.x_markers.push_back(0.5 * (g.start_s + g.end_s) - r.start_s);
    }
    if (!series.empty()) page.svg(report::svgPlot(series, o));
  }
  if (r.gnss_x_m.size() > 1) {
    PlotOptions o;
    o.title = "GNSS fixes (east-north about the first), " + n(r.gnss_fixes) + " fixes, " + f(r.gnss_length_m, 1) + " m";
    o.x_label = "east [m]";
    o.y_label = "north [m]";
    o.equal_axes = true;
    o.width_px = o.height_px = 480;
    page.svg(report::svgPlot({{"RMC fixes", r.gnss_x_m, r.gnss_y_m}}, o));
  }
}

void canSection(report::HtmlPage& page, const CanReport& c) {
  page.heading("CAN bus");
  page.paragraph(c.log + ": " + n(c.frames) + " frames, " + n(c.bad_lines) + " bad lines of " + n(c.lines) +
                 (c.vehicle.empty() ? " (no --vehicle: ids without names, no signals)" : ", decoded as " + c.vehicle));
  if (!c.issues.empty()) {
    std::string t;
    for (const auto& i : c.issues) t += i + "\n";
    page.code(t);
  }
  std::vector<std::vector<std::string>> rows;
  for (const auto& i : c.ids) {
    char id[16];
    std::snprintf(id, sizeof id, i.extended ? "0x%08X" : "0x%03X", i.id);
    rows.push_back({i.iface, id, i.name, n(i.count), f(i.rate_hz), f(i.median_period_s * 1e3, 1),
                    f(i.max_period_s * 1e3, 1), n(i.gaps)});
  }
  page.table({"bus", "id", "message", "frames", "rate [Hz]", "median period [ms]", "max period [ms]", "gaps"}, rows);
  for (const auto& s : c.signals) {
    PlotOptions o;
    o.title = s.name + " [" + s.unit + "]";
    o.x_label = "time since start [s]";
    o.y_label = s.name + " [" + s.unit + "]";
    o.points = false;
    page.svg(report::svgPlot({{s.name, s.t_s, s.value}}, o));
  }
  if (!c.path_x_m.empty()) {
    PlotOptions o;
    o.title = "dead-reckoned path (T_odom_base), " + f(c.path_length_m, 1) + " m";
    o.x_label = "x [m]";
    o.y_label = "y [m]";
    o.points = false;
    o.equal_axes = true;
    o.width_px = o.height_px = 480;
    page.svg(report::svgPlot({{"wheel speeds + yaw rate", c.path_x_m, c.path_y_m}}, o));
  }
}

void mapSection(report::HtmlPage& page, const MapReport& m) {
  page.heading("Map (" + m.dir + ")");
  std::vector<std::vector<std::string>> rows = {{"poses", n(m.poses)}, {"trajectory length [m]", f(m.length_m, 1)}};
  for (const auto& [k, v] : m.summary.items()) rows.push_back({k, v.dump()});
  page.table({"figure", "value"}, rows);
  PlotOptions o;
  o.title = "trajectory (T_map_lidar)";
  o.x_label = "x [m]";
  o.y_label = "y [m]";
  o.points = false;
  o.equal_axes = true;
  o.width_px = o.height_px = 480;
  page.svg(report::svgPlot({{"trajectory.tum", m.x_m, m.y_m}}, o));
  for (const auto& pic : m.pictures) page.pngFile(pic, pic, 800);
}

}  // namespace

std::string toHtml(const RecordingReport& r) {
  report::HtmlPage page("Recording report: " + r.recording);
  std::string files;
  for (const auto& file : r.files) files += (files.empty() ? "" : ", ") + file;
  page.paragraph(r.format + " " + files + ": " + f(r.end_s - r.start_s, 1) + " s from " + utc(r.start_s) + ", " +
                 std::to_string(r.streams.size()) + " streams" +
                 (r.sensor_records ? ", " + std::to_string(r.sensor_records) + " other rawlog records" : ""));
  for (const auto& w : r.warnings) page.paragraph("Warning: " + w + ".");
  if (!r.damage.empty()) page.paragraph("Damaged: " + r.damage + ". The report covers the data before it.");
  sensorSection(page, r);
  if (r.can) canSection(page, *r.can);
  if (r.map) mapSection(page, *r.map);
  return page.str();
}

}  // namespace roadslam::recording_report

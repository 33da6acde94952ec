// The CAN part of the report: frame rates per id (can::analyzeLog), the car's signals decoded in SI
// units (vehicle::VehicleDecoder) and the dead-reckoned path (vehicle::runOdometry).
#include <algorithm>
#include <filesystem>
#include <map>
#include <numeric>
#include <stdexcept>

#include "internal.h"
#include "roadslam/can/candump.h"
#include "roadslam/can/dbc.h"
#include "roadslam/can/log_info.h"
#include "roadslam/vehicle/can_odometry.h"
#include "roadslam/vehicle/vehicle_state.h"

namespace fs = std::filesystem;

namespace roadslam::recording_report {
namespace {

using vehicle::Quantity;

SignalSeries series(const std::string& name, const std::string& unit, const std::vector<double>& t,
                    const std::vector<double>& v, std::size_t max_points) {
  SignalSeries s{name, unit, decimate(t, max_points), decimate(v, max_points), 0, 0, 0};
  if (!v.empty()) {
    s.min = *std::min_element(v.begin(), v.end());
    s.max = *std::max_element(v.begin(), v.end());
    s.mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
  }
  return s;
}

/// Speed, yaw rate and steering angle as the car reports them, each at its own updates.
void decodeSignals(const std::vector<can::CanFrame>& frames, vehicle::VehicleDecoder& dec, const ReportParams& p,
                   CanReport& out) {
  std::vector<double> ts, vs, ty, vy, tst, vst;
  vehicle::VehicleState st;
  for (const auto& f : frames) {
    const vehicle::UpdateMask m = dec.process(f, st);
    if (m & (vehicle::kWheelMask | vehicle::bit(Quantity::kVehicleSpeed)))
      ts.push_back(st.t_s), vs.push_back((st.reverse ? -1.0 : 1.0) * st.speed());
    if (m & vehicle::bit(Quantity::kYawRate)) ty.push_back(st.t_s), vy.push_back(st.value(Quantity::kYawRate));
    if (m & vehicle::bit(Quantity::kSteeringAngle))
      tst.push_back(st.t_s), vst.push_back(st.value(Quantity::kSteeringAngle));
  }
  if (!ts.empty()) out.signals.push_back(series("speed", "m/s", ts, vs, p.max_plot_points));
  if (!ty.empty()) out.signals.push_back(series("yaw_rate", "rad/s", ty, vy, p.max_plot_points));
  if (!tst.empty()) out.signals.push_back(series("steering_angle", "rad", tst, vst, p.max_plot_points));
}

}  // namespace

std::vector<double> decimate(const std::vector<double>& v, std::size_t n) {
  if (n < 2 || v.size() <= n) return v;
  const std::size_t step = (v.size() + n - 2) / (n - 1);
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); i += step) out.push_back(v[i]);
  if ((v.size() - 1) % step != 0) out.push_back(v.back());
  return out;
}

std::vector<std::string> canSidecars(const std::string& path) {
  std::vector<std::string> logs;
  if (!fs::is_directory(path)) return logs;
  for (const auto& e : fs::directory_iterator(path)) {
    const std::string n = e.path().filename().string();
    if (e.is_regular_file() && n.rfind("can_", 0) == 0 && n.find(".candump.log") != std::string::npos)
      logs.push_back(e.path().string());
  }
  std::sort(logs.begin(), logs.end());
  return logs;
}

CanReport readCan(const std::vector<std::string>& logs, const std::string& vehicle_ini, const ReportParams& p,
                  std::vector<PendingStream>& streams) {
  CanReport c;
  std::vector<can::CanFrame> frames;
  for (const std::string& log : logs) {
    can::CandumpStats st;
    auto f = can::readCandumpFile(log, &st);
    frames.insert(frames.end(), f.begin(), f.end());
    c.log += (c.log.empty() ? "" : ", ") + log;
    c.lines += st.lines;
    c.bad_lines += st.bad;
    for (const auto& is : st.issues) {
      if (c.issues.size() >= p.max_listed_issues) break;
      c.issues.push_back(log + ":" + std::to_string(is.line) + ": " + is.reason + " (" + is.text + ")");
    }
    if (f.empty())
      throw std::runtime_error(log + ": no CAN frame in it (" + std::to_string(st.bad) + " of " +
                               std::to_string(st.lines) + " lines unreadable" +
                               (st.issues.empty() ? "" : ", first at line " + std::to_string(st.issues[0].line)) + ")");
  }
  std::stable_sort(frames.begin(), frames.end(), [](const auto& a, const auto& b) { return a.t_us < b.t_us; });
  c.frames = frames.size();
  std::optional<vehicle::VehicleParams> vp;
  std::optional<can::Database> db;
  if (!vehicle_ini.empty()) {
    vp = vehicle::loadVehicleIni(vehicle_ini);
    db = can::loadDbcFile(vp->dbcPath());
    c.vehicle = vp->name;
  }
  const can::LogInfo info = can::analyzeLog(frames, db ? &*db : nullptr, p.gap_factor, p.min_gap_s);
  for (const auto& i : info.ids)
    c.ids.push_back({i.iface, i.id, i.extended, i.name, i.count, i.rate_hz, i.median_period_s, i.max_period_s, i.gaps});
  std::map<std::string, std::vector<double>> by_iface;
  for (const auto& f : frames) by_iface[f.iface.data()].push_back(f.timeSeconds());
  for (auto& [iface, t] : by_iface) {
    PendingStream ps;
    ps.info.label = iface;
    ps.info.kind = "can";
    ps.stamps = std::move(t);
    streams.push_back(std::move(ps));
  }
  if (vp) {
    vehicle::VehicleDecoder signals(*vp, *db);
    decodeSignals(frames, signals, p, c);
    vehicle::VehicleDecoder odo(*vp, *db);
    const auto r = vehicle::runOdometry(frames, odo, vehicle::DeadReckoningParams{});
    std::vector<double> x, y;
    for (const auto& pose : r.poses) x.push_back(pose.x_m), y.push_back(pose.y_m);
    c.path_x_m = decimate(x, p.max_plot_points);
    c.path_y_m = decimate(y, p.max_plot_points);
    c.path_length_m = r.dead_reckoning.distance_m;
    c.dead_reckoning_gap_time_s = r.dead_reckoning.gap_time_s;
  }
  return c;
}

void shiftCanTimes(CanReport& c, double start_s) {
  for (auto& s : c.signals)
    for (double& t : s.t_s) t -= start_s;
}

}  // namespace roadslam::recording_report

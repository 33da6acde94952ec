#include <roadslam/common/atomic_file.h>
#include <roadslam/vehicle/jobs.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <sstream>

namespace roadslam::vehicle {
namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

std::string logLine(const can::CandumpStats& s) {
  std::ostringstream o;
  o << "log: " << s.frames << " frames, " << s.bad << " bad lines" << (s.truncated_tail ? " (truncated tail)" : "");
  for (const auto& i : s.issues) o << "\n  line " << i.line << ": " << i.reason << ": " << i.text;
  return o.str();
}

void writeUsedConfig(const std::string& path, const VehicleParams& v, const DeadReckoningParams& d) {
  mrpt::config::CConfigFileMemory cfg;
  v.saveToConfigFile(cfg, "vehicle");
  d.saveToConfigFile(cfg, "dead_reckoning");
  writeFileAtomically(path, cfg.getContent());
}
}  // namespace

std::string OdometryJobReport::text() const {
  std::ostringstream o;
  const auto& d = result.decode;
  const auto& r = result.dead_reckoning;
  o << logLine(log) << "\n"
    << "decode: " << d.used << " frames used of " << d.frames << ", " << d.short_frames << " short, "
    << d.dlc_mismatch << " DLC mismatch, " << d.other_interface << " other interface\n";
  if (calibrated) {
    o << "calibration vs GNSS: yaw-rate bias " << bias.bias_radps * kRadToDeg << " deg/s (" << bias.fixes
      << " fixes), wheel-speed scale " << scale.scale << " (" << scale.gnss_m << " m GNSS / " << scale.wheels_m
      << " m wheels)" << (used.speed_scale == 1.0 ? ", scale not applied" : "") << "\n";
  }
  o << "dead reckoning: " << r.steps << " steps, " << r.distance_m << " m, standstill " << r.standstill_s
    << " s, " << r.gaps << " gaps (" << r.gap_time_s << " s not integrated), yaw-rate bias in use "
    << result.yaw_rate_bias_radps * kRadToDeg << " deg/s\n";
  if (!result.poses.empty()) {
    const Pose2D& p = result.poses.back();
    o << "final pose: x " << p.x_m << " m, y " << p.y_m << " m, yaw " << p.yaw_rad * kRadToDeg << " deg\n";
  }
  return o.str();
}

OdometryJobReport runOdometryJob(const OdometryJob& job) {
  OdometryJobReport rep;
  const VehicleParams vp = loadVehicleIni(job.vehicle_ini, job.data_root);
  const auto frames = can::readCandumpFile(job.log, &rep.log);
  rep.used = job.dead_reckoning;
  if (!job.gnss_csv.empty()) {
    const auto fixes = loadGnssFixCsv(job.gnss_csv);
    VehicleDecoder first(vp);
    const OdometryResult raw = runOdometry(frames, first, job.dead_reckoning);
    rep.bias = estimateYawRateBias(raw.samples, fixes);
    rep.scale = estimateSpeedScale(raw.samples, fixes);
    rep.calibrated = true;
    if (rep.bias.fixes >= 3) rep.used.yaw_rate_bias_radps = rep.bias.bias_radps;
    if (job.estimate_scale && rep.scale.intervals > 0) rep.used.speed_scale = rep.scale.scale;
  }
  VehicleDecoder dec(vp);
  rep.result = runOdometry(frames, dec, rep.used);
  writeTum(job.out_tum, rep.result.poses);
  writeUsedConfig(job.out_tum + ".ini", vp, rep.used);
  return rep;
}

std::string RawlogJobReport::text() const {
  std::ostringstream o;
  o << logLine(log) << "\n"
    << "decode: " << decode.used << " frames used of " << decode.frames << ", " << decode.short_frames
    << " short, " << decode.dlc_mismatch << " DLC mismatch\n"
    << "rawlog: " << stats.odometry << " CObservationOdometry, " << stats.imu << " CObservationIMU, " << stats.gps
    << " CObservationGPS\n";
  if (!stats.sidecar_path.empty()) o << "sidecar: " << stats.sidecar_path << " (" << stats.sidecar_frames << " frames)\n";
  return o.str();
}

RawlogJobReport runRawlogJob(const RawlogJob& job) {
  RawlogJobReport rep;
  const VehicleParams vp = loadVehicleIni(job.vehicle_ini, job.data_root);
  const auto frames = can::readCandumpFile(job.log, &rep.log);
  VehicleDecoder dec(vp);
  rep.stats = exportRawlog(frames, dec, job.dead_reckoning, job.rawlog, job.out_rawlog);
  rep.decode = dec.stats();
  mrpt::config::CConfigFileMemory cfg;
  vp.saveToConfigFile(cfg, "vehicle");
  job.dead_reckoning.saveToConfigFile(cfg, "dead_reckoning");
  job.rawlog.saveToConfigFile(cfg, "rawlog");
  writeFileAtomically(job.out_rawlog + ".ini", cfg.getContent());
  return rep;
}

}  // namespace roadslam::vehicle

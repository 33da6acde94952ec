// Oracle / end-to-end tests on real logs: RAV4 dead reckoning against the reference trajectory
// (gt_camera_pose_enu_20hz_DERIVED.csv) with the shipped ini, with and without the GNSS wheel-speed
// scale; the Civic log (dropped frames) processed without error and its gaps reported.
#include <roadslam/can/candump.h>
#include <roadslam/vehicle/can_odometry.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using namespace roadslam::vehicle;
namespace fs = std::filesystem;

namespace {
constexpr double kPi = 3.14159265358979323846;
const std::string kData = ROADSLAM_SHARED_DATA;
const std::string kIni = std::string(ROADSLAM_SOURCE_DIR) + "/ini/vehicles/";

struct GtPose {
  double t, e, n, heading;
};
std::vector<GtPose> loadGt(const std::string& path) {
  std::ifstream in(path);
  std::vector<GtPose> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::stringstream ss(line);
    std::vector<double> v;
    for (std::string tok; std::getline(ss, tok, ',');) v.push_back(std::stod(tok));
    out.push_back({v.at(0), v.at(1), v.at(2), v.at(4)});
  }
  return out;
}

Pose2D poseAt(const std::vector<Pose2D>& poses, double t) {
  const auto it = std::lower_bound(poses.begin(), poses.end(), t,
                                   [](const Pose2D& p, double x) { return p.t_s < x; });
  if (it == poses.begin()) return poses.front();
  if (it == poses.end()) return poses.back();
  const Pose2D& a = *(it - 1);
  const Pose2D& b = *it;
  const double f = (t - a.t_s) / (b.t_s - a.t_s);
  Pose2D p = a;
  p.t_s = t;
  p.x_m = a.x_m + f * (b.x_m - a.x_m);
  p.y_m = a.y_m + f * (b.y_m - a.y_m);
  p.yaw_rad = a.yaw_rad + f * std::remainder(b.yaw_rad - a.yaw_rad, 2 * kPi);
  return p;
}

struct Errors {
  double position_pct, heading_deg, path_m;
};

// Dead reckoning started on the reference pose at the first reference time; the start heading is
// the reference's direction of travel over its first 2 s (the camera's yaw mount offset is unknown).
Errors evaluate(const std::vector<roadslam::can::CanFrame>& frames, const VehicleParams& vp,
                const DeadReckoningParams& dp, const std::vector<GtPose>& gt) {
  std::size_t k = 0;
  while (k + 1 < gt.size() && gt[k].t - gt[0].t < 2.0) ++k;
  Pose2D start;
  start.x_m = gt[0].e;
  start.y_m = gt[0].n;
  start.yaw_rad = std::atan2(gt[k].n - gt[0].n, gt[k].e - gt[0].e);
  VehicleDecoder dec(vp);
  const OdometryResult r = runOdometry(frames, dec, dp, start);
  // Re-anchor at the first reference time (odometry starts at the first wheel frame, ~0.04 s earlier).
  const Pose2D p0 = poseAt(r.poses, gt.front().t);
  const Pose2D p1 = poseAt(r.poses, gt.back().t);
  double path = 0;
  for (std::size_t i = 1; i < gt.size(); ++i) path += std::hypot(gt[i].e - gt[i - 1].e, gt[i].n - gt[i - 1].n);
  const double dx = (p1.x_m - p0.x_m) - (gt.back().e - gt.front().e);
  const double dy = (p1.y_m - p0.y_m) - (gt.back().n - gt.front().n);
  const double dyaw_dr = std::remainder(p1.yaw_rad - p0.yaw_rad, 2 * kPi);
  const double dyaw_gt = std::remainder(gt.back().heading - gt.front().heading, 2 * kPi);
  return {100.0 * std::hypot(dx, dy) / path, std::abs(dyaw_dr - dyaw_gt) * 180 / kPi, path};
}
}  // namespace

TEST(Rav4DeadReckoning, AgainstReferenceTrajectory) {
  const std::string dir = kData + "/can/rav4-2017/";
  const std::string log = dir + "rav4_2018-08-02_seg40.candump.log";
  const std::string gt_path = dir + "gt_camera_pose_enu_20hz_DERIVED.csv";
  const std::string gnss_path = dir + "gnss_ublox_fix.csv";
  for (const auto& f : {log, gt_path, gnss_path}) {
    if (!fs::exists(f)) GTEST_SKIP() << "missing " << f;
  }
  const VehicleParams vp = loadVehicleIni(kIni + "toyota-rav4-2017.ini", kData);
  roadslam::can::CandumpStats cs;
  const auto frames = roadslam::can::readCandumpFile(log, &cs);
  EXPECT_EQ(cs.bad, 0U);
  const auto gt = loadGt(gt_path);
  const auto fixes = loadGnssFixCsv(gnss_path);
  ASSERT_GT(gt.size(), 1000U);

  VehicleDecoder dec(vp);
  const OdometryResult raw = runOdometry(frames, dec, DeadReckoningParams{});
  const BiasEstimate bias = estimateYawRateBias(raw.samples, fixes);
  const ScaleEstimate scale = estimateSpeedScale(raw.samples, fixes);

  DeadReckoningParams none;
  DeadReckoningParams with_bias;
  with_bias.yaw_rate_bias_radps = bias.bias_radps;
  DeadReckoningParams with_both = with_bias;
  with_both.speed_scale = scale.scale;
  const Errors e0 = evaluate(frames, vp, none, gt);
  const Errors e1 = evaluate(frames, vp, with_bias, gt);
  const Errors e2 = evaluate(frames, vp, with_both, gt);
  std::cout << "bias " << bias.bias_radps * 180 / kPi << " deg/s from " << bias.fixes << " fixes; scale "
            << scale.scale << " (gnss " << scale.gnss_m << " m / wheels " << scale.wheels_m << " m)\n"
            << "path " << e0.path_m << " m\n"
            << "no calibration:       " << e0.position_pct << " % , heading " << e0.heading_deg << " deg\n"
            << "bias only:            " << e1.position_pct << " % , heading " << e1.heading_deg << " deg\n"
            << "bias + speed scale:   " << e2.position_pct << " % , heading " << e2.heading_deg << " deg\n";
  RecordProperty("bias_deg_s", std::to_string(bias.bias_radps * 180 / kPi));
  RecordProperty("scale", std::to_string(scale.scale));
  RecordProperty("err_pct_bias_only", std::to_string(e1.position_pct));
  RecordProperty("err_pct_bias_scale", std::to_string(e2.position_pct));
  EXPECT_NEAR(e0.path_m, 1012, 5);
  EXPECT_NEAR(bias.bias_radps * 180 / kPi, -0.4, 0.05);  // the manifest's observed offset
  EXPECT_NEAR(scale.scale, 1.01, 0.01);
  EXPECT_GT(e0.heading_deg, 10.0);  // the raw yaw rate is unusable: the bias must matter
  // Measured 2026-11: 0.86 % / 0.07 deg with the bias, 0.39 % / 0.07 deg with bias and scale.
  EXPECT_LT(e1.position_pct, 1.0);
  EXPECT_LT(e1.heading_deg, 0.2);
  EXPECT_LT(e2.position_pct, 0.5);
  EXPECT_LT(e2.heading_deg, 0.2);
  EXPECT_LT(e2.position_pct, e1.position_pct);
}

TEST(Rav4DeadReckoning, YawRateSignAgreesWithSteering) {
  // ISO 8855: left steering (positive) gives a positive (CCW) yaw rate. The correlation of the
  // bias-free yaw rate with the bicycle-model yaw rate from the steering angle must be positive.
  const std::string log = kData + "/can/rav4-2017/rav4_2018-08-02_seg40.candump.log";
  if (!fs::exists(log)) GTEST_SKIP() << "missing " << log;
  const VehicleParams vp = loadVehicleIni(kIni + "toyota-rav4-2017.ini", kData);
  VehicleDecoder dec(vp);
  VehicleState s;
  std::vector<double> a, b;
  for (const auto& f : roadslam::can::readCandumpFile(log)) {
    const UpdateMask m = dec.process(f, s);
    if (!(m & bit(Quantity::kYawRate)) || !s.has(Quantity::kSteeringAngle) || s.speed() < 5) continue;
    a.push_back(s.value(Quantity::kYawRate));
    b.push_back(s.speed() * std::tan(s.value(Quantity::kSteeringAngle) / vp.steering_ratio) / vp.wheelbase_m);
  }
  ASSERT_GT(a.size(), 1000U);
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ma += a[i] / static_cast<double>(a.size());
    mb += b[i] / static_cast<double>(b.size());
  }
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  const double corr = sab / std::sqrt(saa * sbb);
  std::cout << "yaw rate vs steering correlation " << corr << "\n";
  EXPECT_GT(corr, 0.3);
}

TEST(CivicLog, DroppedFramesProcessedAndGapsReported) {
  const std::string log = kData + "/can/civic-2019/civic_typeR_2019_turnonanddrive.candump.log";
  if (!fs::exists(log)) GTEST_SKIP() << "missing " << log;
  const VehicleParams vp = loadVehicleIni(kIni + "honda-civic-2019.ini", kData);
  roadslam::can::CandumpStats cs;
  const auto frames = roadslam::can::readCandumpFile(log, &cs);
  EXPECT_EQ(cs.frames, 28835U);
  EXPECT_EQ(cs.bad, 0U);
  VehicleDecoder dec(vp);
  DeadReckoningParams dp;  // default max_step_s 0.5 s: longer holes are gaps, reported
  const OdometryResult r = runOdometry(frames, dec, dp);
  std::cout << "civic: " << r.decode.used << " frames used, " << r.dead_reckoning.steps << " steps, "
            << r.dead_reckoning.gaps << " gaps (" << r.dead_reckoning.gap_time_s << " s), distance "
            << r.dead_reckoning.distance_m << " m, standstill " << r.dead_reckoning.standstill_s << " s\n";
  EXPECT_EQ(r.decode.short_frames, 0U);
  EXPECT_GT(r.dead_reckoning.steps, 700U);
  EXPECT_GT(r.dead_reckoning.gaps, 0U);
  EXPECT_GT(r.dead_reckoning.distance_m, 5.0);
  for (const Pose2D& p : r.poses) {
    ASSERT_TRUE(std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.yaw_rad));
  }
}

// pipeline::LiveGnss, the online GNSS correction of a live feed: fixes posted as they arrive (here
// out of order, with no-fix epochs among them) against a drifting odometry; the corrected frames
// scored against the synthetic truth (the oracle), the fixes after a frame never used for it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>

#include "roadslam/gnss/geo.h"
#include "roadslam/pipeline/live_gnss.h"

using namespace roadslam;

namespace {
// A 60 s drive at 15 m/s along gentle bends; the odometry turns 0.05 deg/s too fast and is 0.5 % long.
struct Drive {
  std::vector<double> t;
  gnss_fusion::PoseVector truth, odom;
};
Drive drive() {
  Drive d;
  double x = 0, y = 0, yaw = 0.5, ox = 0, oy = 0, oyaw = 0;
  for (double t = 0; t <= 60 + 1e-9; t += 0.1) {
    const double rate = 0.05 * std::sin(2 * M_PI * t / 30);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity(), O = T;
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(x, y, 0);
    O.linear() = Eigen::AngleAxisd(oyaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    O.translation() = Eigen::Vector3d(ox, oy, 0);
    d.t.push_back(1000 + t);
    d.truth.push_back(T);
    d.odom.push_back(O);
    x += 1.5 * std::cos(yaw), y += 1.5 * std::sin(yaw), yaw += rate * 0.1;
    ox += 1.005 * 1.5 * std::cos(oyaw), oy += 1.005 * 1.5 * std::sin(oyaw), oyaw += (rate + 0.05 * M_PI / 180) * 0.1;
  }
  return d;
}
}  // namespace

TEST(LiveGnss, CorrectsTheLiveOdometryInEnu) {
  const Drive d = drive();
  const gnss::EnuFrame world({48.1, 11.5, 500});  // the truth's frame
  gnss_fusion::GnssFusionParams p;
  p.edge_sigma_t_per_m = 0.01;
  p.online_yaw_rate_bias = true;  // a dead reckoning's drift: both states on
  p.online_odometry_scale = true;
  pipeline::LiveGnss live(p);
  uint64_t s = 12345;  // fixed: a small LCG's Box-Muller noise, 1 m
  auto n01 = [&s] {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u1 = ((s >> 11) + 1.0) / 9007199254740993.0;
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u2 = (s >> 11) / 9007199254740992.0;
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
  };
  double sum2 = 0, odo2 = 0, fix2 = 0;
  std::size_t fixes_scored = 0;
  std::size_t scored = 0;
  for (std::size_t i = 0; i < d.t.size(); ++i) {
    if (i % 10 == 5) {  // 1 Hz; each posted 0.2 s late, after the frame of its own time
      gnss::GnssFix f;
      f.t_receive_s = d.t[i - 2];
      const Eigen::Vector3d p_true = d.truth[i - 2].translation();
      const auto g = world.toGeodetic(p_true + Eigen::Vector3d(n01(), n01(), 1.5 * n01()));
      f.position = g;
      f.has_position = true;
      f.hdop = 1.0 / p.uere_m;  // sigma = HDOP x uere = 1 m
      f.quality = i % 100 != 55 ? 1 : 0;  // a no-fix epoch every 10 s
      live.post(f);
      if (f.valid()) {
        fix2 += (world.toEnu(g) - p_true).head<2>().squaredNorm();
        ++fixes_scored;
      }
    }
    const auto T = live.correct(d.t[i], d.odom[i]);
    if (!T || d.t[i] < 1010) continue;  // scored after 10 s
    ASSERT_TRUE(live.origin().has_value());
    const Eigen::Vector3d p_world = world.toEnu(gnss::EnuFrame(*live.origin()).toGeodetic(T->translation()));
    sum2 += (p_world - d.truth[i].translation()).head<2>().squaredNorm();
    odo2 += (d.odom[i].translation() - d.truth[i].translation()).head<2>().squaredNorm();
    ++scored;
  }
  const auto c = live.counts();
  EXPECT_EQ(c.epochs, 60u);
  EXPECT_EQ(c.no_fix, 6u);
  EXPECT_EQ(c.fixes, 54u) << "every valid fix posted up to the last frame";
  EXPECT_TRUE(c.anchored);
  ASSERT_GT(scored, 400u);
  const double ate = std::sqrt(sum2 / scored), odo = std::sqrt(odo2 / scored), fix = std::sqrt(fix2 / fixes_scored);
  EXPECT_LT(ate, 0.9 * fix) << "fixes alone " << fix << " m, odometry alone " << odo << " m";
  EXPECT_GT(odo, 10.0) << "the drift the fixes have to correct";
  EXPECT_NE(live.statusLine().find("54 fixes (6 no fix)"), std::string::npos) << live.statusLine();
  std::cout << live.statusLine() << "; 2D ATE after 10 s " << ate << " m, fixes alone " << fix << " m, odometry alone " << odo << " m\n";
}

namespace {
// Two GPS sources on one feed: GNSS (the truth + 1 m noise, 1 Hz) and CAN_GPS, whose fixes sit 20 m east of
// the truth (another antenna, another datum); a CAN_GPS record without a fix comes first.
struct TwoSources {
  double rms_truth = 0, rms_shifted = 0;  ///< corrected frames after 10 s against the truth, and the truth + 20 m east [m]
  pipeline::LiveGnssCounts c;
  std::string status;
};
TwoSources runTwoSources(const std::string& label) {
  const Drive d = drive();
  const gnss::EnuFrame world({48.1, 11.5, 500});
  const Eigen::Vector3d shift(20, 0, 0);
  gnss_fusion::GnssFusionParams p;
  p.edge_sigma_t_per_m = 0.01;
  p.online_yaw_rate_bias = true;
  p.online_odometry_scale = true;
  p.live_source_label = label;
  pipeline::LiveGnss live(p);
  uint64_t s = 777;  // fixed
  auto n01 = [&s] {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u1 = ((s >> 11) + 1.0) / 9007199254740993.0;
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * (s >> 11) / 9007199254740992.0);
  };
  auto post = [&](std::size_t i, const char* source, const Eigen::Vector3d& offset, bool valid) {
    gnss::GnssFix f;
    f.t_receive_s = d.t[i];
    f.position = world.toGeodetic(d.truth[i].translation() + offset + Eigen::Vector3d(n01(), n01(), 0));
    f.has_position = true;
    f.hdop = 1.0 / p.uere_m;
    f.quality = valid ? 1 : 0;
    f.label = source;
    live.post(f);
  };
  TwoSources r;
  std::size_t n = 0;
  for (std::size_t i = 0; i < d.t.size(); ++i) {
    if (i == 0) post(i, "CAN_GPS", shift, false);
    if (i % 10 == 3) post(i, "GNSS", Eigen::Vector3d::Zero(), true);
    if (i % 10 == 8) post(i, "CAN_GPS", shift, true);
    const auto T = live.correct(d.t[i], d.odom[i]);
    if (!T || d.t[i] < 1010) continue;
    const Eigen::Vector3d p_world = world.toEnu(gnss::EnuFrame(*live.origin()).toGeodetic(T->translation()));
    r.rms_truth += (p_world - d.truth[i].translation()).head<2>().squaredNorm();
    r.rms_shifted += (p_world - d.truth[i].translation() - shift).head<2>().squaredNorm();
    ++n;
  }
  r.rms_truth = std::sqrt(r.rms_truth / std::max<std::size_t>(n, 1));
  r.rms_shifted = std::sqrt(r.rms_shifted / std::max<std::size_t>(n, 1));
  r.c = live.counts();
  r.status = live.statusLine();
  std::cout << (label.empty() ? "first seen" : label) << ": " << r.status << "; RMS to the truth " << r.rms_truth
            << " m, to the truth + 20 m east " << r.rms_shifted << " m\n";
  return r;
}
}  // namespace

// One source is fused, never the mix (a mix would sit about 10 m from both): without a label the first
// source with a fix (GNSS: CAN_GPS's first record had none), with [gnss_fusion] live_source_label the one named.
TEST(LiveGnss, FusesOneSourceTheFirstWithAFixOrTheOneNamed) {
  const TwoSources first = runTwoSources("");
  EXPECT_EQ(first.c.source, "GNSS");
  EXPECT_FALSE(first.c.source_chosen);
  EXPECT_EQ(first.c.epochs, 60u) << "GNSS's 60; CAN_GPS's no-fix record before any source had a fix is CAN_GPS's";
  EXPECT_EQ(first.c.no_fix, 0u);
  EXPECT_EQ(first.c.fixes, 60u);
  EXPECT_EQ(first.c.other_sources, 61u);
  EXPECT_LT(first.rms_truth, 1.0);
  EXPECT_GT(first.rms_shifted, 15.0);
  EXPECT_NE(first.status.find("GNSS from GNSS (first seen; 61 records of other sources left out): 60 fixes (0 no fix)"),
            std::string::npos)
      << first.status;
  const TwoSources named = runTwoSources("CAN_GPS");
  EXPECT_EQ(named.c.source, "CAN_GPS");
  EXPECT_TRUE(named.c.source_chosen);
  EXPECT_EQ(named.c.epochs, 61u);
  EXPECT_EQ(named.c.no_fix, 1u);
  EXPECT_EQ(named.c.other_sources, 60u);
  EXPECT_LT(named.rms_shifted, 1.0);
  EXPECT_GT(named.rms_truth, 15.0);
  EXPECT_NE(named.status.find("GNSS from CAN_GPS (live_source_label; 60 records"), std::string::npos) << named.status;
}

// The no-fix records that arrive before any source has a fix are counted under their own source once
// one is chosen: here 2 of GNSS (its own no fix) and 3 of CAN_GPS (left out), not 5 under GNSS.
TEST(LiveGnss, NoFixRecordsBeforeTheChoiceCountUnderTheirOwnSource) {
  pipeline::LiveGnss live(gnss_fusion::GnssFusionParams{});
  auto post = [&live](const char* label, bool valid) {
    gnss::GnssFix f;
    f.label = label;
    f.position = {48.1, 11.5, 500};
    f.has_position = true;
    f.quality = valid ? 1 : 0;
    f.hdop = 1;
    live.post(f);
  };
  for (const char* l : {"CAN_GPS", "GNSS", "CAN_GPS", "GNSS", "CAN_GPS"}) post(l, false);
  pipeline::LiveGnssCounts c = live.counts();
  EXPECT_TRUE(c.source.empty());
  EXPECT_EQ(c.epochs, 5u) << "no source yet: every record, none with a fix";
  EXPECT_EQ(c.no_fix, 5u);
  post("GNSS", true);
  post("CAN_GPS", true);
  c = live.counts();
  EXPECT_EQ(c.source, "GNSS");
  EXPECT_EQ(c.epochs, 3u);
  EXPECT_EQ(c.no_fix, 2u);
  EXPECT_EQ(c.other_sources, 4u);
}

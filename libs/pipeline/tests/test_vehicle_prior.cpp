// The CAN motion prior: the lidar motion between two times against world poses of an analytic
// drive (arc), coverage limits, params round trip. Simulated drives: test_vehicle_prior_sim.cpp.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <iostream>

#include "roadslam/pipeline/vehicle_prior.h"

using namespace roadslam;
using namespace roadslam::pipeline;
using vehicle::Quantity;

namespace {
vehicle::VehicleParams wheelsAndGyro() {
  vehicle::VehicleParams vp;
  for (Quantity q : {Quantity::kWheelFL, Quantity::kWheelFR, Quantity::kWheelRL, Quantity::kWheelRR,
                     Quantity::kYawRate})
    vp.map[static_cast<std::size_t>(q)].signal = "M.S";
  return vp;
}

/// World pose of the base on a circular arc driven at v, w from the origin (heading +x) at time t.
Eigen::Isometry3d arcPose(double v, double w, double t) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(w * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(v / w * std::sin(w * t), v / w * (1 - std::cos(w * t)), 0);
  return T;
}

VehiclePriorParams mounted() {
  VehiclePriorParams p;
  p.T_base_lidar.translation() = Eigen::Vector3d(1.2, 0.3, 1.9);
  p.T_base_lidar.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return p;
}
}  // namespace

TEST(VehiclePrior, LidarMotionOnAnArcMatchesWorldPoses) {
  const double v = 10, w = 0.2, t0 = 1000;
  const VehiclePriorParams p = mounted();
  VehiclePrior prior(p, wheelsAndGyro());
  vehicle::VehicleState st;
  for (int i = 0; i <= 300; ++i) {  // 100 Hz for 3 s
    st.t_s = t0 + 0.01 * i;
    for (Quantity q : {Quantity::kWheelFL, Quantity::kWheelFR, Quantity::kWheelRL, Quantity::kWheelRR})
      st.v[static_cast<std::size_t>(q)] = v;
    st.v[static_cast<std::size_t>(Quantity::kYawRate)] = w;
    st.valid = vehicle::kWheelMask | vehicle::bit(Quantity::kYawRate);
    prior.update(st, vehicle::kWheelMask | vehicle::bit(Quantity::kYawRate));
  }
  EXPECT_FALSE(prior.between(t0 - 1, t0 + 1).has_value());       // before the first CAN pose
  EXPECT_FALSE(prior.between(t0 + 1, t0 + 3.5).has_value());      // too far past the newest
  ASSERT_TRUE(prior.between(t0 + 2.9, t0 + 3.05).has_value());    // short extrapolation
  const double ta = 1.234, tb = 1.334;  // between two sweeps 0.1 s apart, off the 10 ms grid
  const auto m = prior.between(t0 + ta, t0 + tb);
  ASSERT_TRUE(m.has_value());
  // The integration starts at the first update (t0): world poses of the lidar from the arc.
  const Eigen::Isometry3d Wa = arcPose(v, w, ta) * p.T_base_lidar, Wb = arcPose(v, w, tb) * p.T_base_lidar;
  const Eigen::Isometry3d want = Wa.inverse() * Wb;
  EXPECT_LT((m->T_prev_curr.translation() - want.translation()).norm(), 2e-3)
      << m->T_prev_curr.translation().transpose() << " vs " << want.translation().transpose();
  EXPECT_LT(Eigen::AngleAxisd(m->T_prev_curr.linear().transpose() * want.linear()).angle(), 1e-4);
  EXPECT_NEAR(m->speed_mps, v, 1e-9);
  // lidar rotated by 90 deg: forward driving is along -y of the lidar
  EXPECT_LT(m->T_prev_curr.translation().y(), -0.9);
}

TEST(VehiclePrior, ParamsRoundTripAndBadValuesNamed) {
  VehiclePriorParams p = mounted();
  p.max_extrapolation_s = 0.2;
  p.dead_reckoning.yaw_rate_bias_radps = 0.01;
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg, "vehicle_prior");
  VehiclePriorParams q;
  q.loadFromConfigFile(cfg, "vehicle_prior");
  EXPECT_TRUE(q.T_base_lidar.isApprox(p.T_base_lidar, 1e-9));
  EXPECT_DOUBLE_EQ(q.max_extrapolation_s, 0.2);
  EXPECT_NEAR(q.dead_reckoning.yaw_rate_bias_radps, 0.01, 1e-7);  // ini doubles are written with %e
  cfg.write("vehicle_prior", "history_s", std::string("-1"));
  try {
    q.loadFromConfigFile(cfg, "vehicle_prior");
    FAIL() << "negative history_s accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("history_s"), std::string::npos) << e.what();
  }
}

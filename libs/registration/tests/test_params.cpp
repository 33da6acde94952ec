#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roadslam/registration/adaptive_threshold.h>
#include <roadslam/registration/params.h>

#include <cmath>

namespace roadslam::registration {
namespace {

TEST(Params, SaveLoadRoundTripAndUnitConversion) {
  Params p;
  p.method = Method::Ndt;
  p.kernel = Kernel::Tukey;
  p.max_correspondence_distance_m = 1.25;
  p.convergence_rotation_rad = 0.01 * M_PI / 180.0;
  p.ndt_resolution_m = 0.75;
  p.ndt_levels = 2;
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg, "registration");
  EXPECT_NEAR(cfg.read_double("registration", "convergence_rotation_deg", 0), 0.01, 1e-12);
  EXPECT_EQ(cfg.read_string("registration", "method", ""), "ndt");
  Params q;
  q.loadFromConfigFile(cfg, "registration");
  EXPECT_EQ(q.method, Method::Ndt);
  EXPECT_EQ(q.kernel, Kernel::Tukey);
  EXPECT_DOUBLE_EQ(q.max_correspondence_distance_m, 1.25);
  EXPECT_NEAR(q.convergence_rotation_rad, p.convergence_rotation_rad, 1e-15);
  EXPECT_DOUBLE_EQ(q.ndt_resolution_m, 0.75);
  EXPECT_EQ(q.ndt_levels, 2);
}

TEST(Params, BadValuesNameTheKey) {
  mrpt::config::CConfigFileMemory cfg;
  cfg.write("r", "method", std::string("gicp"));
  Params p;
  try {
    p.loadFromConfigFile(cfg, "r");
    FAIL() << "accepted method = gicp";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("method"), std::string::npos) << e.what();
  }
  mrpt::config::CConfigFileMemory cfg2;
  cfg2.write("r", "max_correspondance_distance_m", 1.0);  // typo
  try {
    p.loadFromConfigFile(cfg2, "r");
    FAIL() << "accepted an unknown key";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("max_correspondance_distance_m"), std::string::npos) << e.what();
  }
}

TEST(AdaptiveThreshold, ThreeSigmaOfModelDeviations) {
  AdaptiveThreshold th(2.0, 0.1, 100.0);
  EXPECT_DOUBLE_EQ(th.threshold(), 2.0);
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  motion.translation().x() = 1.0;
  Eigen::Isometry3d dev = Eigen::Isometry3d::Identity();
  dev.translation().y() = 0.1;
  th.update(dev, Eigen::Isometry3d::Identity());  // standstill: not counted
  EXPECT_DOUBLE_EQ(th.threshold(), 2.0);
  th.update(dev, motion);
  EXPECT_NEAR(th.threshold(), 0.3, 1e-12);
  Eigen::Isometry3d rot = Eigen::Isometry3d::Identity();
  rot.linear() = Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  th.update(rot, motion);  // 2 * 100 * sin(0.001) = 0.2 m
  EXPECT_NEAR(th.threshold(), 3.0 * std::sqrt((0.01 + std::pow(200 * std::sin(0.001), 2)) / 2), 1e-9);
}

}  // namespace
}  // namespace roadslam::registration

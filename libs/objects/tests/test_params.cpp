// [objects] / [tracking]: every key saved is read back; bad values are errors naming the section.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "roadslam/objects/params.h"

using namespace roadslam::objects;

TEST(ObjectsParams, SaveLoadRoundTrip) {
  ClusterParams c;
  c.enabled = true, c.method = ClusterMethod::Dbscan, c.cluster_distance_m = 0.8, c.lshape_step_rad = 0.02;
  c.dbscan_min_points = 6, c.map_delay_s = 1.5;
  TrackerParams t;
  t.gate_m = 3.3, t.max_misses = 7, t.motion_model = MotionModel::Ctrv, t.ctrv.yaw_accel_sigma_radps2 = 0.25;
  mrpt::config::CConfigFileMemory ini;
  c.saveToConfigFile(ini);
  t.saveToConfigFile(ini);
  ClusterParams c2;
  TrackerParams t2;
  c2.loadFromConfigFile(ini);
  t2.loadFromConfigFile(ini);
  EXPECT_TRUE(c2.enabled);
  EXPECT_EQ(c2.method, ClusterMethod::Dbscan);
  EXPECT_EQ(c2.dbscan_min_points, 6);
  EXPECT_DOUBLE_EQ(c2.map_delay_s, 1.5);
  EXPECT_DOUBLE_EQ(c2.cluster_distance_m, 0.8);
  EXPECT_NEAR(c2.lshape_step_rad, 0.02, 1e-7);  // saved in degrees, as text
  EXPECT_DOUBLE_EQ(t2.gate_m, 3.3);
  EXPECT_EQ(t2.max_misses, 7);
  EXPECT_EQ(t2.motion_model, MotionModel::Ctrv);
  EXPECT_NEAR(t2.ctrv.yaw_accel_sigma_radps2, 0.25, 1e-7);
}

TEST(ObjectsParams, ImmKeysRoundTrip) {
  TrackerParams t;
  t.motion_model = MotionModel::Imm, t.imm.max_turn_rate_radps = 1.2, t.imm.ct_sojourn_s = 3.5, t.imm.init_ct_probability = 0.2;
  mrpt::config::CConfigFileMemory ini;
  t.saveToConfigFile(ini);
  EXPECT_EQ(ini.read_string("tracking", "motion_model", ""), "imm");
  TrackerParams t2;
  t2.loadFromConfigFile(ini);
  EXPECT_EQ(t2.motion_model, MotionModel::Imm);
  EXPECT_NEAR(t2.imm.max_turn_rate_radps, 1.2, 1e-7);  // saved in deg/s, as text
  EXPECT_DOUBLE_EQ(t2.imm.ct_sojourn_s, 3.5);
  EXPECT_DOUBLE_EQ(t2.imm.init_ct_probability, 0.2);
  ini.write("tracking", "imm_init_ct_probability", 1.5);
  try {
    t2.loadFromConfigFile(ini);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("[tracking]"), std::string::npos) << e.what();
  }
}

TEST(ObjectsParams, BadValuesNameTheSection) {
  mrpt::config::CConfigFileMemory ini;
  ini.write("objects", "method", std::string("kmeans"));
  ClusterParams c;
  try {
    c.loadFromConfigFile(ini);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("[objects]"), std::string::npos);
  }
  mrpt::config::CConfigFileMemory ini2;
  ini2.write("tracking", "gate_m", -1.0);
  TrackerParams t;
  EXPECT_THROW(t.loadFromConfigFile(ini2), std::runtime_error);
  mrpt::config::CConfigFileMemory ini3;
  ini3.write("tracking", "output_max_misses", -1);
  EXPECT_THROW(t.loadFromConfigFile(ini3), std::runtime_error);
  mrpt::config::CConfigFileMemory ini4;
  ini4.write("objects", "ground_max_bridge_m", -1.0);
  try {
    c.loadFromConfigFile(ini4);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("ground_max_bridge_m"), std::string::npos);
  }
}

// The objects' ground labels: [preprocess] seg_* with the bridge capped by [objects] ground_max_bridge_m
// (0 keeps the odometry's), never widened.
TEST(ObjectsParams, TheObjectsGroundBridgesAtMostTheirOwnLimit) {
  ClusterParams c;
  c.ground.max_bridge_m = 30.0;
  EXPECT_DOUBLE_EQ(c.groundParams().max_bridge_m, c.ground_max_bridge_m);
  c.ground_max_bridge_m = 0;
  EXPECT_DOUBLE_EQ(c.groundParams().max_bridge_m, 30.0);
  c.ground_max_bridge_m = 50.0;
  EXPECT_DOUBLE_EQ(c.groundParams().max_bridge_m, 30.0);
}

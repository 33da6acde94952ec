// Built-in manual tables against VeloView's XML files (loaded by MRPT's parser) and MRPT's own
// default tables; rings by elevation; XML errors name the file.
#include <gtest/gtest.h>

#include <mrpt/obs/VelodyneCalibration.h>

#include <cmath>
#include <fstream>

#include "oracle_util.h"
#include "roadslam/velodyne/calibration.h"

using namespace roadslam::velodyne;

namespace {

using roadslam::velodyne::test::dataFile;

void expectSameTable(const Calibration& a, const Calibration& b, double tol_rad) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a.lasers[i].vertical_rad, b.lasers[i].vertical_rad, tol_rad) << "laser " << i;
    EXPECT_NEAR(a.lasers[i].azimuth_correction_rad, b.lasers[i].azimuth_correction_rad, 1e-9);
    EXPECT_NEAR(a.lasers[i].distance_correction_m, b.lasers[i].distance_correction_m, 1e-9);
    EXPECT_NEAR(a.lasers[i].vertical_offset_m, b.lasers[i].vertical_offset_m, 1e-9);
    EXPECT_NEAR(a.lasers[i].horizontal_offset_m, b.lasers[i].horizontal_offset_m, 1e-9);
    EXPECT_EQ(a.lasers[i].ring, b.lasers[i].ring) << "laser " << i;
  }
}

}  // namespace

TEST(Calibration, BuiltinVlp16EqualsVeloViewXml) {
  const std::string xml = dataFile("veloview_calib_VLP-16.xml");
  if (!std::ifstream(xml)) GTEST_SKIP() << "missing " << xml;
  const Calibration file = Calibration::fromXmlFile(xml);
  EXPECT_EQ(file.model, Model::VLP16);
  expectSameTable(Calibration::builtinVlp16(), file, 1e-9);
}

TEST(Calibration, BuiltinHdl32EqualsVeloViewXml) {
  const std::string xml = dataFile("veloview_calib_HDL-32.xml");
  if (!std::ifstream(xml)) GTEST_SKIP() << "missing " << xml;
  const Calibration file = Calibration::fromXmlFile(xml);
  EXPECT_EQ(file.model, Model::HDL32);
  expectSameTable(Calibration::builtinHdl32(), file, 1e-6);  // XML: 9.3299999 vs 9.33
}

TEST(Calibration, BuiltinTablesEqualMrptDefaults) {
  for (const auto& [name, ours] : {std::pair<std::string, Calibration>{"VLP16", Calibration::builtinVlp16()},
                                   {"HDL32", Calibration::builtinHdl32()}}) {
    const auto& m = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration(name);
    ASSERT_EQ(m.laser_corrections.size(), ours.size()) << name;
    for (std::size_t i = 0; i < ours.size(); ++i)
      EXPECT_NEAR(ours.lasers[i].vertical_rad, m.laser_corrections[i].verticalCorrection * M_PI / 180,
                  1e-6) << name << " laser " << i;
  }
}

TEST(Calibration, RingsFollowElevation) {
  const Calibration c = Calibration::builtinVlp16();
  EXPECT_EQ(c.lasers[0].ring, 0);    // -15 deg
  EXPECT_EQ(c.lasers[15].ring, 15);  // +15 deg
  EXPECT_EQ(c.lasers[1].ring, 8);    // +1 deg
  EXPECT_EQ(c.lasers[14].ring, 7);   // -1 deg
  const Calibration h = Calibration::builtinHdl32();
  EXPECT_EQ(h.lasers[0].ring, 0);    // -30.67 deg
  EXPECT_EQ(h.lasers[31].ring, 31);  // +10.67 deg
}

TEST(Calibration, BadXmlThrowsNamingTheFile) {
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/velodyne_bad_calib.xml";
  std::ofstream(path) << "<not><a calibration/></not>";
  for (const std::string& p : {path, std::string("/nonexistent/calib.xml")}) {
    try {
      Calibration::fromXmlFile(p);
      FAIL() << "no exception for " << p;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(Calibration::builtin(Model::Unknown), std::invalid_argument);
}

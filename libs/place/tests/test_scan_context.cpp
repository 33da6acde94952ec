// Scan Context on synthetic streets: a sweep turned by a known yaw matches itself with that yaw (Kim &
// Kim 2018: the descriptor is rotation invariant up to a column shift); another street does not match;
// the database only offers entries min_travel_m back.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <roadslam/place/scan_context.h>

#include <Eigen/Geometry>
#include <random>

namespace roadslam::place {
namespace {

using Cloud = std::vector<Eigen::Vector3d>;

/// A street seen from its centre: road at -1.9 m and buildings of random heights on both sides [m].
Cloud street(uint32_t seed, uint32_t sampling_seed) {
  std::mt19937 rng(seed), srng(sampling_seed);
  std::uniform_real_distribution<double> h(6, 20), u(0, 1);
  Cloud pts;
  for (double x0 = -60; x0 < 60; x0 += 10) {
    for (double side : {-1.0, 1.0}) {
      const double height = h(rng), setback = 8 + 4 * u(rng);
      for (int k = 0; k < 400; ++k) pts.emplace_back(x0 + 10 * u(srng), side * setback, -1.9 + height * u(srng));
    }
  }
  for (int k = 0; k < 4000; ++k) pts.emplace_back(120 * u(srng) - 60, 16 * u(srng) - 8, -1.9);
  return pts;
}

Cloud turned(const Cloud& c, double yaw) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Cloud out;
  for (const auto& p : c) out.push_back(R * p);
  return out;
}

TEST(ScanContext, SamePlaceTurnedMatchesWithItsYaw) {
  const ScanContextParams p;
  const ScanContext a = makeScanContext(street(1, 10), p);
  const double yaw = 66.0 * M_PI / 180.0;  // 11 sectors of 6 deg
  const ScanContext b = makeScanContext(turned(street(1, 11), yaw), p);
  int shift = 0;
  const double d = scanContextDistance(a, b, &shift);
  EXPECT_LT(d, p.max_distance);
  EXPECT_NEAR(shift * 360.0 / p.num_sectors, 66.0, 6.0);
  const double other = scanContextDistance(a, makeScanContext(street(2, 10), p));
  EXPECT_GT(other, d + 0.05) << "another street";
}

TEST(ScanContext, DatabaseReturnsOnlyOldPlacesWithTheirYaw) {
  ScanContextParams p;
  p.min_travel_m = 50;
  ScanContextDatabase db(p);
  for (uint32_t s = 0; s < 120; ++s) db.add(100 + s, 5.0 * s, makeScanContext(street(s, 1000 + s), p));
  // revisit of place 7 turned 180 deg, at path 700 m: found with yaw ~pi
  const auto m = db.query(makeScanContext(turned(street(7, 5), M_PI), p), 700.0, 3);
  ASSERT_FALSE(m.empty());
  EXPECT_EQ(m.front().id, 107u);
  EXPECT_NEAR(std::abs(m.front().yaw_rad), M_PI, 0.11);
  // the same place at a path only 20 m later: too recent, not offered
  const auto recent = db.query(makeScanContext(street(119, 6), p), 5.0 * 119 + 20, 3);
  for (const auto& r : recent) EXPECT_NE(r.id, 219u);
}

TEST(ScanContext, EmptySweepMatchesNothing) {
  ScanContextParams p;
  p.min_travel_m = 0;
  ScanContextDatabase db(p);
  db.add(0, 0, makeScanContext(street(1, 1), p));
  EXPECT_TRUE(db.query(makeScanContext({}, p), 100).empty());
}

TEST(ScanContext, ParamsRoundTripAndBadValues) {
  ScanContextParams a;
  a.num_sectors = 72;
  a.max_distance = 0.15;
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg);
  ScanContextParams b;
  b.loadFromConfigFile(cfg);
  EXPECT_EQ(b.num_sectors, 72);
  EXPECT_DOUBLE_EQ(b.max_distance, 0.15);
  cfg.write("place_recognition", "num_sectors", std::string("2"));
  EXPECT_THROW(b.loadFromConfigFile(cfg), std::runtime_error);
}

}  // namespace
}  // namespace roadslam::place

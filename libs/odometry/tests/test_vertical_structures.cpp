// Up direction from vertical structures (vertical_structures.h) on synthetic scenes whose true
// tilt is known: walls and a pole seen from a tilted sensor, with ground and a leaning trunk.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "roadslam/odometry/vertical_structures.h"

using namespace roadslam::odometry;

namespace {

constexpr double kDeg = M_PI / 180.0;

struct Scene {
  std::vector<Eigen::Vector3d> pts;  // world frame, z up
  std::vector<uint8_t> ground;
  std::mt19937 rng{7};
  std::normal_distribution<double> noise{0.0, 0.01};

  void add(const Eigen::Vector3d& p, bool g = false) {
    pts.push_back(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    ground.push_back(g);
  }
  // Wall through \p origin spanned by the horizontal unit \p along and z, \p len x \p height.
  void wall(const Eigen::Vector3d& origin, const Eigen::Vector3d& along, double len, double height) {
    for (double s = 0; s < len; s += 0.1)
      for (double z = 0; z < height; z += 0.25) add(origin + s * along + Eigen::Vector3d(0, 0, z));
  }
  // Cylinder of radius \p r around the axis from \p base along unit \p axis.
  void cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double r, double len) {
    const Eigen::Vector3d a = axis.unitOrthogonal(), b = axis.cross(a);
    for (double s = 0; s < len; s += 0.2)
      for (double t = 0; t < 2 * M_PI; t += 0.5) add(base + s * axis + r * (std::cos(t) * a + std::sin(t) * b));
  }
  void road() {
    for (double x = -20; x < 20; x += 0.3)
      for (double y = -6; y < 6; y += 0.3) add({x, y, -1.9}, true);
  }
};

Eigen::Matrix3d tilt(double roll_deg, double pitch_deg) {
  return (Eigen::AngleAxisd(roll_deg * kDeg, Eigen::Vector3d::UnitX()) *
          Eigen::AngleAxisd(pitch_deg * kDeg, Eigen::Vector3d::UnitY()))
      .toRotationMatrix();
}

std::vector<Eigen::Vector3d> toLidar(const std::vector<Eigen::Vector3d>& w, const Eigen::Matrix3d& R_world_lidar) {
  std::vector<Eigen::Vector3d> out;
  for (const auto& p : w) out.push_back(R_world_lidar.transpose() * p);
  return out;
}

/// The geometry alone: every structure weighted by its own fit (no lean floor).
VerticalStructureParams fitOnly() {
  VerticalStructureParams p;
  p.lean_rad = 0;
  return p;
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::min(1.0, a.normalized().dot(b.normalized()))) / kDeg;
}

}  // namespace

TEST(VerticalStructures, WallsAndPoleGiveTheUpDirectionOfATiltedSensor) {
  Scene s;
  s.road();
  s.wall({-15, 8, -1.9}, Eigen::Vector3d::UnitX(), 30, 8);    // facade along the street
  s.wall({12, -10, -1.9}, Eigen::Vector3d::UnitY(), 20, 8);   // facade across it
  s.cylinder({5, -5, -1.9}, Eigen::Vector3d::UnitZ(), 0.1, 5);  // pole
  const Eigen::Matrix3d R = tilt(3.0, -2.0);
  const auto pts = toLidar(s.pts, R);
  const Eigen::Vector3d up_true = R.transpose() * Eigen::Vector3d::UnitZ();

  const auto cs = findVerticalStructures(pts, s.ground, Eigen::Vector3d::UnitZ(), fitOnly());
  ASSERT_GT(cs.size(), 20u);
  Eigen::Vector2d info;
  const Eigen::Vector3d up = upFromScatter(verticalScatter(cs, Eigen::Matrix3d::Identity()), Eigen::Vector3d::UnitZ(), &info);
  EXPECT_LT(angleDeg(up, up_true), 0.1);  // measured 0.07 deg with 1 cm noise (0 without)
  EXPECT_GT(info.minCoeff(), 0.1 * info.maxCoeff());  // two wall orientations + pole: both tilts seen
  // Rotated into the world frame, the same constraints give the world's z.
  const Eigen::Vector3d up_world = upFromScatter(verticalScatter(cs, R), Eigen::Vector3d::UnitZ());
  EXPECT_LT(angleDeg(up_world, Eigen::Vector3d::UnitZ()), 0.1);
}

TEST(VerticalStructures, ParallelWallsLeaveTheTiltAboutTheirNormalUnseen) {
  Scene s;
  s.road();
  s.wall({-15, 8.5, -1.9}, Eigen::Vector3d::UnitX(), 30, 8);
  s.wall({-15, -7.5, -1.9}, Eigen::Vector3d::UnitX(), 30, 8);
  const auto cs = findVerticalStructures(s.pts, s.ground, Eigen::Vector3d::UnitZ(), fitOnly());
  ASSERT_FALSE(cs.empty());
  Eigen::Vector2d info;
  upFromScatter(verticalScatter(cs, Eigen::Matrix3d::Identity()), Eigen::Vector3d::UnitZ(), &info);
  EXPECT_LT(info.minCoeff(), 1e-3 * info.maxCoeff());
}

TEST(VerticalStructures, GroundAndStronglyLeaningTrunksGiveNoConstraint) {
  Scene s;
  s.road();
  // Road points not flagged as ground would be a horizontal plane: its normal is vertical, gated out.
  std::vector<uint8_t> none;
  EXPECT_TRUE(findVerticalStructures(s.pts, none, Eigen::Vector3d::UnitZ(), VerticalStructureParams{}).empty());
  Scene t;
  t.cylinder({5, -5, -1.9}, Eigen::Vector3d(std::sin(30 * kDeg), 0, std::cos(30 * kDeg)), 0.1, 5);
  EXPECT_TRUE(findVerticalStructures(t.pts, t.ground, Eigen::Vector3d::UnitZ(), VerticalStructureParams{}).empty());
}

// With the lean floor no structure counts for more than 1 / lean^2 (a 30 m facade seen by many
// points is known to the fit to hundredths of a degree, but stands vertical only to its lean), and
// a poorly fitted one keeps its own, smaller weight.
TEST(VerticalStructures, NoStructureCountsForMoreThanItsLean) {
  Scene s;
  s.road();
  s.wall({-15, 8.5, -1.9}, Eigen::Vector3d::UnitX(), 30, 8);  // mid-voxel: not cut by a face
  VerticalStructureParams p;
  p.lean_rad = 0.5 * kDeg;
  const auto capped = findVerticalStructures(s.pts, s.ground, Eigen::Vector3d::UnitZ(), p);
  const auto free = findVerticalStructures(s.pts, s.ground, Eigen::Vector3d::UnitZ(), fitOnly());
  ASSERT_EQ(capped.size(), free.size());
  ASSERT_FALSE(capped.empty());
  const double cap = 1.0 / (p.lean_rad * p.lean_rad);
  for (size_t i = 0; i < capped.size(); ++i) {
    EXPECT_LT(capped[i].weight, cap);
    EXPECT_NEAR(capped[i].weight, 1.0 / (1.0 / free[i].weight + p.lean_rad * p.lean_rad), 1e-6 * cap);
  }
  double max_free = 0;
  for (const auto& c : free) max_free = std::max(max_free, c.weight);
  EXPECT_GT(max_free, 2 * cap) << "the facade's fit alone would outweigh its lean";  // measured 5.4x
}

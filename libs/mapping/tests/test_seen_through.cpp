// The seen-through pass on sweeps ray-cast in a known scene: a car present in the first sweep only
// (a trail) goes, the ground, a wall, a thin pole and a parked car every sweep sees stay.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>

#include "roadslam/mapping/seen_through.h"

using namespace roadslam;
using namespace roadslam::mapping;

namespace {

constexpr double kLidarHeight = 1.9;  // lidar above the flat ground z = 0 [m]

struct Box {
  Eigen::Vector3d lo, hi;
};

enum class Hit { None, Ground, Wall, Pole, Parked, Moving };

/// Slab test (Kay & Kajiya 1986): entry distance of the ray o + t d into \p b, if any.
std::optional<double> hitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& b) {
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) {
      if (o[i] < b.lo[i] || o[i] > b.hi[i]) return std::nullopt;
      continue;
    }
    double a = (b.lo[i] - o[i]) / d[i], c = (b.hi[i] - o[i]) / d[i];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
  }
  if (t0 > t1) return std::nullopt;
  return t0;
}

/// The scene seen from a lidar at (x, 0, 1.9): VLP-16 rings (-15..15 deg every 2 deg), 0.4 deg azimuth
/// steps, 100 m reach. The moving car is there only when \p with_moving.
struct Scene {
  Box wall{{-50, 12, 0}, {150, 12.5, 8}};
  Box pole{{20, -6.1, 0}, {20.1, -6.0, 5}};  // 0.1 m thin
  Box parked{{30, 5, 0}, {34.5, 6.8, 1.5}};
  Box moving{{12, -4.5, 0}, {16.5, -2.7, 1.5}};

  std::vector<std::pair<Eigen::Vector3f, Hit>> sweep(double x, bool with_moving) const {
    std::vector<std::pair<Eigen::Vector3f, Hit>> out;
    const Eigen::Vector3d o(x, 0, kLidarHeight);
    for (int ring = 0; ring < 16; ++ring) {
      const double el = (-15.0 + 2.0 * ring) * M_PI / 180;
      for (double az = -180; az < 180; az += 0.4) {
        const double a = az * M_PI / 180;
        const Eigen::Vector3d d(std::cos(el) * std::cos(a), std::cos(el) * std::sin(a), std::sin(el));
        double best = 100.0;
        Hit what = Hit::None;
        if (d.z() < 0) best = std::min(best, -o.z() / d.z()), what = best < 100.0 ? Hit::Ground : Hit::None;
        auto consider = [&](const Box& b, Hit h) {
          if (auto t = hitBox(o, d, b); t && *t < best) best = *t, what = h;
        };
        consider(wall, Hit::Wall);
        consider(pole, Hit::Pole);
        consider(parked, Hit::Parked);
        if (with_moving) consider(moving, Hit::Moving);
        if (what != Hit::None) out.push_back({(best * d).cast<float>(), what});  // lidar frame = world - o
      }
    }
    return out;
  }
};

}  // namespace

TEST(SeenThrough, RemovesATrailKeepsTheStaticScene) {
  const Scene scene;
  std::vector<Keyframe> kfs;
  PoseVector T_map_kf;
  std::vector<std::vector<Hit>> labels;
  for (int k = 0; k <= 40; ++k) {
    const double x = 1.0 * k;
    Keyframe kf;
    kf.frame_index = k;
    kf.path_m = x;
    std::vector<Hit> lab;
    for (const auto& [p, h] : scene.sweep(x, k == 0)) kf.points_lidar.push_back(p), lab.push_back(h);
    kfs.push_back(std::move(kf));
    labels.push_back(std::move(lab));
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(x, 0, kLidarHeight);
    T_map_kf.push_back(T);
  }
  SeenThroughParams p;
  p.enabled = true;
  const double voxel_m = 0.2;
  SeenThroughStats st;
  const auto dynamic = findSeenThrough(kfs, T_map_kf, voxel_m, p, &st);
  EXPECT_EQ(st.references, 21u);  // every 2 m of the 40 m path
  // count, per kind, the points whose voxel is dynamic
  std::map<Hit, std::pair<int, int>> gone;  // kind -> (removed, all)
  for (size_t k = 0; k < kfs.size(); ++k) {
    for (size_t i = 0; i < kfs[k].points_lidar.size(); ++i) {
      const Eigen::Vector3f m = T_map_kf[k].cast<float>() * kfs[k].points_lidar[i];
      const Eigen::Vector3i key = (m / static_cast<float>(voxel_m)).array().floor().cast<int>().matrix();
      auto& [removed, all] = gone[labels[k][i]];
      ++all;
      removed += dynamic.count(key) > 0;
    }
  }
  const auto& [car_removed, car_all] = gone[Hit::Moving];
  ASSERT_GT(car_all, 50);
  // the car's points above the ground filter (0.3 m) nearly all go; the lowest stay with the ground
  EXPECT_GE(car_removed, 0.8 * car_all) << car_removed << " of " << car_all;
  std::printf("moving car: %d of %d points removed\n", car_removed, car_all);
  for (Hit h : {Hit::Ground, Hit::Wall, Hit::Pole, Hit::Parked}) {
    EXPECT_EQ(gone[h].first, 0) << "kind " << static_cast<int>(h) << ": " << gone[h].first << " of " << gone[h].second;
    EXPECT_GT(gone[h].second, 0);
  }
}

TEST(SeenThrough, ParamsRoundTripAndBadValuesAreNamed) {
  SeenThroughParams a;
  a.enabled = true;
  a.ray_tolerance_m = 0.25;
  a.azimuth_res_rad = 0.5 * M_PI / 180;
  mrpt::config::CConfigFileMemory mem;
  a.saveToConfigFile(mem);
  SeenThroughParams b;
  b.loadFromConfigFile(mem);
  EXPECT_TRUE(b.enabled);
  EXPECT_DOUBLE_EQ(b.ray_tolerance_m, 0.25);
  EXPECT_NEAR(b.azimuth_res_rad, a.azimuth_res_rad, 1e-12);
  mem.write("seen_through", "min_through", 0);
  try {
    b.loadFromConfigFile(mem);
    FAIL() << "min_through = 0 accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("[seen_through]"), std::string::npos) << e.what();
  }
}

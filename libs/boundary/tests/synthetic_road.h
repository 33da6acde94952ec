#pragma once
// A VLP-16-like sweep cast analytically over a straight road: flat road at -sensor_height, curbs
// (sidewalks raised by curb_h) beyond y = left_y and y = right_y, optional boxes (cars, walls).
// Independent of the detector: the expected boundaries are the curb lines themselves.
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include "roadslam/common/scan.h"

namespace roadslam::boundary::test {

struct Box {
  double x0, x1, y0, y1, z0, z1;  ///< lidar frame [m]
};

struct Road {
  double sensor_height = 1.9;              ///< [m]
  std::optional<double> left_y = 4.0;      ///< curb line, left [m]; nullopt = open ground
  std::optional<double> right_y = -3.5;    ///< curb line, right [m]
  double curb_h = 0.15;                    ///< [m]
  std::vector<Box> boxes;
  double noise = 0.01;                     ///< range noise sigma [m]
};

inline std::optional<double> hitBox(const Box& b, const double o[3], const double d[3]) {
  double t0 = 0, t1 = 1e9;
  const double lo[3] = {b.x0, b.y0, b.z0}, hi[3] = {b.x1, b.y1, b.z1};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < lo[k] || o[k] > hi[k]) return std::nullopt;
      continue;
    }
    double a = (lo[k] - o[k]) / d[k], c = (hi[k] - o[k]) / d[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a), t1 = std::min(t1, c);
  }
  if (t0 > t1) return std::nullopt;
  return t0;
}

/// Range along direction d (unit) to the road surface, or nullopt (sky).
inline std::optional<double> hitRoad(const Road& r, const double d[3]) {
  if (d[2] >= -1e-6) return std::nullopt;
  const double H = r.sensor_height;
  auto onWalk = [&](double y) { return (r.left_y && y > *r.left_y) || (r.right_y && y < *r.right_y); };
  const double t = H / -d[2];
  if (!onWalk(t * d[1])) return t;
  const double tw = (H - r.curb_h) / -d[2];
  if (onWalk(tw * d[1])) return tw;
  const double yc = d[1] > 0 ? *r.left_y : *r.right_y;  // the ray meets the curb face
  return yc / d[1];
}

inline Scan castSweep(const Road& r, unsigned seed = 1) {
  static const double kElev[16] = {-15, -13, -11, -9, -7, -5, -3, -1, 1, 3, 5, 7, 9, 11, 13, 15};
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, r.noise);
  Scan s;
  s.has_rings = s.has_point_times = true;
  const double o[3] = {0, 0, 0};
  for (int a = 0; a < 1800; ++a) {
    const double az = (a * 0.2 - 180.0) * M_PI / 180.0;
    for (int ring = 0; ring < 16; ++ring) {
      const double e = kElev[ring] * M_PI / 180.0;
      const double d[3] = {std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e)};
      std::optional<double> t = hitRoad(r, d);
      for (const auto& b : r.boxes) {
        const auto tb = hitBox(b, o, d);
        if (tb && (!t || *tb < *t)) t = tb;
      }
      if (!t || *t > 100 || *t < 1.0) continue;
      const double rr = *t + n(rng);
      ScanPoint p;
      p.x = static_cast<float>(rr * d[0]), p.y = static_cast<float>(rr * d[1]), p.z = static_cast<float>(rr * d[2]);
      p.ring = static_cast<uint16_t>(ring);
      p.t = static_cast<float>(a * 0.1 / 1800);
      s.points.push_back(p);
    }
  }
  return s;
}

}  // namespace roadslam::boundary::test

#pragma once
// Test fixture: a VLP-16-like sweep (16 rings -15..15 deg, 1800 azimuths, 10 Hz) cast analytically
// over a flat straight road: the road at -sensor_height, sidewalks raised by curb_h beyond the curb
// lines y = left_y and y = right_y, boxes (cars, walls) on it; fixed-seed range noise. Every point's
// surface and true height are known, independent of the code under test. Shared by the ground
// segmentation's tests here and, downstream, by libs/boundary's tests and bench.
#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "roadslam/common/scan.h"

namespace roadslam::preprocess::fixtures {

struct Box {
  double x0, x1, y0, y1, z0, z1;  ///< lidar frame [m]
};

struct Road {
  double sensor_height = 1.9;            ///< lidar above the road [m]
  std::optional<double> left_y = 4.0;    ///< curb line, left [m]; nullopt = open ground
  std::optional<double> right_y = -3.5;  ///< curb line, right [m]
  double curb_h = 0.15;                  ///< [m]
  std::vector<Box> boxes;
  double noise = 0.01;                   ///< range noise sigma [m]
};

enum class Surface { Road, Sidewalk, CurbFace, Box };

struct PointTruth {
  Surface surface;
  double height_m;  ///< above the road surface under the point (sidewalk: above the sidewalk) [m]
};

/// Range from the lidar along the unit direction \p d to \p b (slab method), or nullopt.
inline std::optional<double> hitBox(const Box& b, const double d[3]) {
  double t0 = 0, t1 = 1e9;
  const double lo[3] = {b.x0, b.y0, b.z0}, hi[3] = {b.x1, b.y1, b.z1};
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (0 < lo[k] || 0 > hi[k]) return std::nullopt;
      continue;
    }
    double a = lo[k] / d[k], c = hi[k] / d[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a), t1 = std::min(t1, c);
  }
  if (t0 > t1) return std::nullopt;
  return t0;
}

/// Range to the road, a sidewalk or a curb face along \p d, with the surface hit; nullopt: sky.
inline std::optional<std::pair<double, Surface>> hitRoad(const Road& r, const double d[3]) {
  if (d[2] >= -1e-6) return std::nullopt;
  const double H = r.sensor_height;
  auto onWalk = [&](double y) { return (r.left_y && y > *r.left_y) || (r.right_y && y < *r.right_y); };
  const double t = H / -d[2];
  if (!onWalk(t * d[1])) return std::make_pair(t, Surface::Road);
  const double tw = (H - r.curb_h) / -d[2];
  if (onWalk(tw * d[1])) return std::make_pair(tw, Surface::Sidewalk);
  return std::make_pair((d[1] > 0 ? *r.left_y : *r.right_y) / d[1], Surface::CurbFace);
}

/// The sweep (returns from 1 to 100 m; rings and point times set). \p truth, when given, gets each
/// point's surface and true height, in the order of the points.
inline Scan castSweep(const Road& r, unsigned seed = 1, std::vector<PointTruth>* truth = nullptr) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, r.noise);
  Scan s;
  s.has_rings = s.has_point_times = true;
  for (int a = 0; a < 1800; ++a) {
    const double az = (a * 0.2 - 180.0) * M_PI / 180.0;
    for (int ring = 0; ring < 16; ++ring) {
      const double e = (-15.0 + 2.0 * ring) * M_PI / 180.0;
      const double d[3] = {std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e)};
      auto hit = hitRoad(r, d);
      for (const auto& b : r.boxes)
        if (const auto tb = hitBox(b, d); tb && (!hit || *tb < hit->first)) hit = std::make_pair(*tb, Surface::Box);
      if (!hit || hit->first > 100 || hit->first < 1.0) continue;
      const double rr = hit->first + n(rng);
      ScanPoint p;
      p.x = static_cast<float>(rr * d[0]), p.y = static_cast<float>(rr * d[1]), p.z = static_cast<float>(rr * d[2]);
      p.ring = static_cast<uint16_t>(ring);
      p.t = static_cast<float>(a * 0.1 / 1800);
      s.points.push_back(p);
      if (truth) {
        const double z = hit->first * d[2] + r.sensor_height;
        truth->push_back({hit->second, hit->second == Surface::Sidewalk ? z - r.curb_h : z});
      }
    }
  }
  return s;
}

/// A car parked perpendicular to the curb at \p curb_y (side +1 left, -1 right), its side from x0 to
/// x0 + 1.8 m, as libs/sim's addParkedCar: body 0.25-1.0 m above the road, 4.4 m long, 0.3 m off
/// the curb; cabin 1.0-1.5 m, 1 m back from the ends. Returns the body.
inline Box addParkedCar(Road& r, double x0, double curb_y, int side) {
  const double H = r.sensor_height, front = curb_y - side * 0.3, end = front - side * 4.4;
  const Box body{x0, x0 + 1.8, std::min(front, end), std::max(front, end), -H + 0.25, -H + 1.0};
  r.boxes.push_back(body);
  const double c0 = end + side * 1.0, c1 = front - side * 1.0;
  r.boxes.push_back({x0 + 0.1, x0 + 1.7, std::min(c0, c1), std::max(c0, c1), -H + 1.0, -H + 1.5});
  return body;
}

/// An aisle of ini/sim/parking-lot.ini seen from its right lane: curbs 9.5 m left and 6.5 m right,
/// 5 m perpendicular bays on both sides in 2.7 m slots, every fifth slot empty (80 % taken), shifted
/// by \p dx along the aisle (the vehicle driving on). Returns the car bodies.
inline std::vector<Box> parkingAisle(Road& r, double dx = 0) {
  r.left_y = 9.5, r.right_y = -6.5;
  std::vector<Box> bodies;
  int slot = 0;
  for (double x = -30; x < 45; x += 2.7, ++slot) {
    if (slot % 5 == 2) continue;
    bodies.push_back(addParkedCar(r, x + 0.4 - dx, 9.5, +1));
    bodies.push_back(addParkedCar(r, x - dx, -6.5, -1));
  }
  return bodies;
}

}  // namespace roadslam::preprocess::fixtures

#include "synthetic_boxes.h"

#include "roadslam/objects/params.h"

#include <cmath>
#include <limits>

namespace roadslam::objects::test {

Scan castSweep(const std::vector<SynthBox>& boxes, int azimuth_steps, double sensor_height_m) {
  Scan s;
  s.has_rings = true;
  s.has_point_times = true;
  for (int k = 0; k < azimuth_steps; ++k) {
    const double az = 2 * M_PI * k / azimuth_steps;
    for (int ring = 0; ring < 16; ++ring) {
      const double el = (-15.0 + 2.0 * ring) * M_PI / 180;
      const double dx = std::cos(el) * std::cos(az), dy = std::cos(el) * std::sin(az), dz = std::sin(el);
      double best = 100.0;
      if (dz < 0) best = std::min(best, sensor_height_m / -dz);
      for (const SynthBox& b : boxes) {
        // slab test in the box frame (origin at the box's footprint centre, z from the road)
        const double c = std::cos(b.yaw), si = std::sin(b.yaw);
        const double ox = c * (-b.cx) + si * (-b.cy), oy = -si * (-b.cx) + c * (-b.cy), oz = sensor_height_m;
        const double rx = c * dx + si * dy, ry = -si * dx + c * dy, rz = dz;
        double t0 = 0, t1 = std::numeric_limits<double>::max();
        const double o[3] = {ox, oy, oz}, r[3] = {rx, ry, rz};
        const double lo[3] = {-b.length / 2, -b.width / 2, 0}, hi[3] = {b.length / 2, b.width / 2, b.height};
        bool hit = true;
        for (int a = 0; a < 3 && hit; ++a) {
          if (std::abs(r[a]) < 1e-12) {
            hit = o[a] >= lo[a] && o[a] <= hi[a];
            continue;
          }
          double ta = (lo[a] - o[a]) / r[a], tb = (hi[a] - o[a]) / r[a];
          if (ta > tb) std::swap(ta, tb);
          t0 = std::max(t0, ta), t1 = std::min(t1, tb);
          hit = t0 <= t1;
        }
        if (hit && t0 > 0) best = std::min(best, t0);
      }
      if (best >= 100.0) continue;
      ScanPoint p;
      p.x = static_cast<float>(best * dx), p.y = static_cast<float>(best * dy), p.z = static_cast<float>(best * dz);
      p.ring = static_cast<uint16_t>(ring);
      p.t = static_cast<float>(0.1 * k / azimuth_steps);
      s.points.push_back(p);
    }
  }
  return s;
}

std::vector<SynthBox> streetScene() {
  return {{8, 4, 0, 4.5, 1.8, 1.5},     {16, 4.2, 0.05, 4.2, 1.8, 1.4}, {25, 4, 0, 4.8, 1.9, 1.6},
          {12, -3.5, M_PI, 4.5, 1.8, 1.5}, {-10, -4, 0.3, 4.4, 1.8, 1.5}, {-20, 4, -0.2, 5.0, 2.0, 1.8},
          {5, -12, 1.2, 4.5, 1.8, 1.5},  {-6, 10, 0.7, 0.6, 0.6, 1.8}};
}

const LabelledSweep& streetSweep() {
  static const LabelledSweep s = [] {
    LabelledSweep w;
    w.scan = castSweep(streetScene());
    w.g = preprocess::segmentGroundWithHeights(w.scan.points, ClusterParams{}.ground);
    return w;
  }();
  return s;
}

}  // namespace roadslam::objects::test

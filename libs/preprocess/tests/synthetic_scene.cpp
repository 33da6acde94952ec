#include "synthetic_scene.h"

#include <cmath>
#include <limits>
#include <random>

namespace roadslam::preprocess::fixtures {
namespace {
struct Hit {
  double t = std::numeric_limits<double>::infinity();
  bool ground = false;
};

double roadZ(const StreetScene& s, double x, double y) {
  const double along = x < s.crest_x_m ? s.slope_near * x
                                       : s.slope_near * s.crest_x_m + s.slope_far * (x - s.crest_x_m);
  return -s.sensor_height_m + along + s.slope_lateral * y;
}

void consider(Hit& h, double t, bool ground) {
  if (t > 1e-6 && t < h.t) h = {t, ground};
}

/// Surface z = roadZ + offset on one slope piece: z = a x + b y + c with a, c of that piece.
void castSurface(const StreetScene& s, const double d[3], double a, double c, double offset,
                 double y_lo, double y_hi, double x_lo, double x_hi, Hit& h) {
  const double den = d[2] - a * d[0] - s.slope_lateral * d[1];
  if (std::abs(den) < 1e-12) return;
  const double t = (c + offset) / den;
  const double x = t * d[0], y = std::abs(t * d[1]);
  if (x >= x_lo && x < x_hi && y >= y_lo && y < y_hi) consider(h, t, true);
}

void castVertical(const StreetScene& s, const double d[3], double y_plane, double lo_off, double hi_off,
                  Hit& h) {
  if (std::abs(d[1]) < 1e-12) return;
  const double t = y_plane / d[1];
  const double z = t * d[2], g = roadZ(s, t * d[0], y_plane);
  if (z >= g + lo_off && z <= g + hi_off) consider(h, t, false);
}

void castBox(const StreetScene& s, const double d[3], Hit& h) {
  const double g = roadZ(s, 10.0, 0.0);
  const double lo[3] = {8.0, -1.0, g}, hi[3] = {12.0, 1.0, g + 1.5};
  double t0 = 0, t1 = 1e9;
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-12) {
      if (0 < lo[k] || 0 > hi[k]) return;
      continue;
    }
    double a = lo[k] / d[k], b = hi[k] / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a), t1 = std::min(t1, b);
  }
  if (t0 <= t1) consider(h, t0, false);
}

Hit cast(const StreetScene& s, const double d[3]) {
  Hit h;
  const double inf = std::numeric_limits<double>::infinity();
  const double c_near = -s.sensor_height_m;
  const double a_far = s.slope_far, c_far = -s.sensor_height_m + (s.slope_near - s.slope_far) * s.crest_x_m;
  for (double off : {0.0, s.curb_height_m}) {
    const double y_lo = off == 0.0 ? 0.0 : s.road_half_width_m;
    const double y_hi = off == 0.0 ? s.road_half_width_m : s.wall_y_m;
    castSurface(s, d, s.slope_near, c_near, off, y_lo, y_hi, -inf, s.crest_x_m, h);
    castSurface(s, d, a_far, c_far, off, y_lo, y_hi, s.crest_x_m, inf, h);
  }
  for (double side : {-1.0, 1.0}) {
    castVertical(s, d, side * s.road_half_width_m, 0.0, s.curb_height_m, h);
    castVertical(s, d, side * s.wall_y_m, s.curb_height_m, s.curb_height_m + s.wall_height_m, h);
  }
  if (s.with_box) castBox(s, d, h);
  return h;
}
}  // namespace

double terrainZ(const StreetScene& s, double x, double y) {
  return roadZ(s, x, y) + (std::abs(y) >= s.road_half_width_m ? s.curb_height_m : 0.0);
}

LabelledScan makeStreetSweep(const StreetScene& s) {
  LabelledScan out;
  out.scan.has_rings = true;
  std::mt19937 rng(static_cast<uint32_t>(s.seed));
  std::normal_distribution<double> noise(0.0, s.range_noise_m);
  for (int a = 0; a < s.azimuth_steps; ++a) {
    const double az = 2 * M_PI * a / s.azimuth_steps;
    for (int ring = 0; ring < 16; ++ring) {
      const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0;
      const double d[3] = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)};
      const Hit h = cast(s, d);
      if (!(h.t < 100.0)) continue;
      const double r = h.t + noise(rng);
      ScanPoint p;
      p.x = static_cast<float>(r * d[0]);
      p.y = static_cast<float>(r * d[1]);
      p.z = static_cast<float>(r * d[2]);
      p.intensity = h.ground ? 10.f : 80.f;
      p.ring = static_cast<uint16_t>(ring);
      out.scan.points.push_back(p);
      out.ground.push_back(h.ground);  // truth = the surface hit, however close to the ground
    }
  }
  return out;
}

}  // namespace roadslam::preprocess::fixtures

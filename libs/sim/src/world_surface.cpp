// RoadSurface: the crowned carriageway and the roughness height field, and their exact ray crossing.
#include <algorithm>
#include <cmath>

#include "roadslam/sim/world.h"

namespace roadslam::sim {

void RoadSurface::seedWaves(uint64_t seed) {
  Rng rng{mix64(seed ^ 0x20AD5EEDull)};
  for (int k = 0; k < kWaves; ++k) {
    const double dir = rng.uniform(0, 2 * M_PI), lambda = roughness_wavelength_m * rng.uniform(0.5, 2.0);
    wave_kx[k] = 2 * M_PI / lambda * std::cos(dir);
    wave_ky[k] = 2 * M_PI / lambda * std::sin(dir);
    wave_phase[k] = rng.uniform(0, 2 * M_PI);
  }
  // kWaves independent sinusoids of amplitude A have variance kWaves A^2 / 2.
  wave_amplitude_m = roughness_m * std::sqrt(2.0 / kWaves);
}

double RoadSurface::roughness(double x, double y) const {
  if (roughness_m == 0) return 0;
  double h = 0;
  for (int k = 0; k < kWaves; ++k) h += std::sin(wave_kx[k] * x + wave_ky[k] * y + wave_phase[k]);
  return wave_amplitude_m * h;
}

namespace {
/// Crown height above the road edges at signed lateral offset \p lat [m].
double crown(double slope, double hw, double lat) { return slope * std::max(0.0, hw - std::abs(lat)); }
}  // namespace

double World::surfaceOffset(double x, double y) const {
  if (!surface.any()) return 0;
  return surface.roughness(x, y) + crownOffset(x, y);
}

double World::crownOffset(double x, double y) const {
  double off = 0;
  const int ix = static_cast<int>(std::floor((x - x0_) / cell_)), iy = static_cast<int>(std::floor((y - y0_) / cell_));
  if (!crown_.empty() && ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_) {
    const CrownLine& c = crown_[static_cast<std::size_t>(iy) * nx_ + ix];
    off += crown(surface.cross_slope, c.hw, (x - c.px) * c.dy - (y - c.py) * c.dx);
  }
  return off;
}

void World::buildCrownLines() {
  crown_.clear();
  if (surface.cross_slope == 0) return;
  crown_.assign(cells_.size(), CrownLine{});
  std::vector<double> best(cells_.size(), 1e300);
  // The nearest centreline sample (and its segment's direction) within reach of each cell centre;
  // on a road's straight parts the crown is exact, on a curve of radius R the tangent line is off
  // by d^2 / 2R laterally (d < 3.6 m from the sample at 0.5 m spacing in a 5 m cell).
  const double reach = 0.75 * cell_;
  for (const Road& r : roads) {
    const std::size_t n = r.centerline.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 p = r.centerline[i], q = r.centerline[(i + 1 < n) ? i + 1 : (r.closed ? 0 : i)];
      const Vec2 o = r.centerline[i > 0 ? i - 1 : (r.closed ? n - 1 : i)];
      const double h = std::atan2(q.y - o.y, q.x - o.x);
      const double ext = r.half_width_m + reach;
      const int ix0 = std::max(0, static_cast<int>((p.x - ext - x0_) / cell_));
      const int ix1 = std::min(nx_ - 1, static_cast<int>((p.x + ext - x0_) / cell_));
      const int iy0 = std::max(0, static_cast<int>((p.y - ext - y0_) / cell_));
      const int iy1 = std::min(ny_ - 1, static_cast<int>((p.y + ext - y0_) / cell_));
      for (int iy = iy0; iy <= iy1; ++iy)
        for (int ix = ix0; ix <= ix1; ++ix) {
          const double dx = x0_ + (ix + 0.5) * cell_ - p.x, dy = y0_ + (iy + 0.5) * cell_ - p.y;
          const double d2 = dx * dx + dy * dy;
          const std::size_t k = static_cast<std::size_t>(iy) * nx_ + ix;
          if (d2 > ext * ext || d2 >= best[k]) continue;
          best[k] = d2;
          crown_[k] = {p.x, p.y, std::cos(h), std::sin(h), r.half_width_m};
        }
    }
  }
  for (std::size_t k = 0; k < cells_.size(); ++k)
    cells_[k].zmax += static_cast<float>(surface.cross_slope * crown_[k].hw);
}

double World::crownedGroundHit(const Ray& ray, const CrownLine& cl, double f0, double a, double t_in,
                               double t_out, double offset) const {
  // g(t) = f0 + a t - crown(lat(t)) - offset is linear between the crown's breakpoints
  // lat = -hw, 0, hw (lat(t) = l0 + lt t): the first sign change is found exactly.
  const double l0 = (ray.o.x - cl.px) * cl.dy - (ray.o.y - cl.py) * cl.dx;
  const double lt = ray.d.x * cl.dy - ray.d.y * cl.dx;
  const double s = surface.cross_slope;
  auto g = [&](double t) { return f0 + a * t - crown(s, cl.hw, l0 + lt * t) - offset; };
  double bps[5] = {t_in, 0, 0, 0, 0};
  int nb = 1;
  if (lt != 0 && cl.hw > 0)
    for (double lb : {-cl.hw, 0.0, cl.hw}) {
      const double t = (lb - l0) / lt;
      if (t > t_in && t < t_out) bps[nb++] = t;
    }
  for (int i = 2; i < nb; ++i)  // insertion sort of the <= 3 breakpoints
    for (int j = i; j > 1 && bps[j] < bps[j - 1]; --j) std::swap(bps[j], bps[j - 1]);
  bps[nb++] = t_out;
  double ga = g(bps[0]);
  if (t_in > 0 && ga < 0) return t_in;  // entered the cell below its surface: a step
  for (int i = 1; i < nb; ++i) {
    const double gb = g(bps[i]);
    if (ga >= 0 && gb < 0) return bps[i - 1] + ga / (ga - gb) * (bps[i] - bps[i - 1]);
    ga = gb;
  }
  return -1;
}

double World::roughGroundHit(const Ray& ray, const CrownLine& cl, double f0, double a, double t_in,
                             double t_out) const {
  // The ray cannot meet the surface before it is below crown + B nor after it is below crown - B
  // (B bounds |roughness|): march that stretch in steps of 1/16 of the central wavelength across
  // the ground (4+ samples per period of the shortest wave), then bisect the first sign change.
  const double B = surface.roughnessBound();
  const double t1 = crownedGroundHit(ray, cl, f0, a, t_in, t_out, B);
  if (t1 < 0) return -1;
  const double t2 = crownedGroundHit(ray, cl, f0, a, t_in, t_out, -B);
  const double t_end = t2 < 0 ? t_out : t2;
  const double lat0 = (ray.o.x - cl.px) * cl.dy - (ray.o.y - cl.py) * cl.dx;
  const double latd = ray.d.x * cl.dy - ray.d.y * cl.dx;
  auto g = [&](double t) {
    return f0 + a * t - crown(surface.cross_slope, cl.hw, lat0 + latd * t) -
           surface.roughness(ray.o.x + t * ray.d.x, ray.o.y + t * ray.d.y);
  };
  double ta = t1, ga = g(ta);
  if (ga < 0) return ta;  // entered the cell below the surface (a step), or grazing at t1
  double step = surface.roughness_wavelength_m / 16 / std::max(1e-6, std::hypot(ray.d.x, ray.d.y));
  step = std::max(step, (t_end - t1) / 512);
  while (ta < t_end) {
    double tb = std::min(ta + step, t_end);
    const double gb = g(tb);
    if (gb < 0) {
      for (int i = 0; i < 30 && tb - ta > 1e-7; ++i) {
        const double tm = 0.5 * (ta + tb);
        (g(tm) < 0 ? tb : ta) = tm;
      }
      return tb;
    }
    ta = tb;
  }
  return -1;
}

}  // namespace roadslam::sim

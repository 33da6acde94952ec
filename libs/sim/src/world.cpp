#include "roadslam/sim/world.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadslam::sim {

namespace {
constexpr double kTwoPi = 6.283185307179586;
enum RefType : uint32_t { kPrism = 0, kCylinder = 1, kSphere = 2 };
constexpr uint32_t kIndexMask = (1u << 30) - 1;
}  // namespace

double Ground::height(double x, double y) const {
  if (amplitude_m == 0) return 0;
  return amplitude_m * (std::sin(kTwoPi * x / wavelength_m) +
                        0.5 * std::sin(kTwoPi * y / (0.8 * wavelength_m)));
}

Vec2 Ground::gradient(double x, double y) const {
  if (amplitude_m == 0) return {0, 0};
  const double k = kTwoPi / wavelength_m;
  return {amplitude_m * k * std::cos(k * x), 0.5 * amplitude_m * (k / 0.8) * std::cos(k * y / 0.8)};
}

void World::buildGrid(double xmin, double ymin, double xmax, double ymax, double cell_m) {
  cell_ = cell_m;
  x0_ = xmin;
  y0_ = ymin;
  nx_ = std::max(1, static_cast<int>(std::ceil((xmax - xmin) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((ymax - ymin) / cell_)));
  cells_.assign(static_cast<std::size_t>(nx_) * ny_, Cell{});
  for (int iy = 0; iy < ny_; ++iy)
    for (int ix = 0; ix < nx_; ++ix) {
      Cell& c = cells_[static_cast<std::size_t>(iy) * nx_ + ix];
      const double xc = x0_ + (ix + 0.5) * cell_, yc = y0_ + (iy + 0.5) * cell_;
      const Vec2 g = ground.gradient(xc, yc);
      c.gz = ground.height(xc, yc);
      c.gx = g.x;
      c.gy = g.y;
      c.zmax = static_cast<float>(c.gz + 0.5 * cell_ * (std::abs(g.x) + std::abs(g.y)));
    }
  // Asphalt where the cell centre is on a carriageway.
  for (const Road& r : roads)
    for (const Vec2& p : r.centerline) {
      const int ix0 = static_cast<int>((p.x - r.half_width_m - x0_) / cell_);
      const int ix1 = static_cast<int>((p.x + r.half_width_m - x0_) / cell_);
      const int iy0 = static_cast<int>((p.y - r.half_width_m - y0_) / cell_);
      const int iy1 = static_cast<int>((p.y + r.half_width_m - y0_) / cell_);
      for (int iy = std::max(0, iy0); iy <= std::min(ny_ - 1, iy1); ++iy)
        for (int ix = std::max(0, ix0); ix <= std::min(nx_ - 1, ix1); ++ix) {
          const double dx = x0_ + (ix + 0.5) * cell_ - p.x, dy = y0_ + (iy + 0.5) * cell_ - p.y;
          if (dx * dx + dy * dy <= r.half_width_m * r.half_width_m)
            cells_[static_cast<std::size_t>(iy) * nx_ + ix].ground_material = Material::Asphalt;
        }
    }
  // Bin every primitive into the cells its footprint overlaps (two passes: count, then fill).
  std::vector<std::vector<uint32_t>> bins(cells_.size());
  auto bin = [&](double bx0, double by0, double bx1, double by1, double ztop, uint32_t ref) {
    const int ix0 = std::max(0, static_cast<int>(std::floor((bx0 - x0_) / cell_)));
    const int ix1 = std::min(nx_ - 1, static_cast<int>(std::floor((bx1 - x0_) / cell_)));
    const int iy0 = std::max(0, static_cast<int>(std::floor((by0 - y0_) / cell_)));
    const int iy1 = std::min(ny_ - 1, static_cast<int>(std::floor((by1 - y0_) / cell_)));
    for (int iy = iy0; iy <= iy1; ++iy)
      for (int ix = ix0; ix <= ix1; ++ix) {
        const std::size_t k = static_cast<std::size_t>(iy) * nx_ + ix;
        bins[k].push_back(ref);
        cells_[k].zmax = std::max(cells_[k].zmax, static_cast<float>(ztop));
      }
  };
  for (std::size_t i = 0; i < prisms.size(); ++i) {
    double a, b, c, d;
    footprintBounds(prisms[i], a, b, c, d);
    bin(a, b, c, d, topMax(prisms[i]), static_cast<uint32_t>(i) | (kPrism << 30));
  }
  for (std::size_t i = 0; i < cylinders.size(); ++i) {
    const Cylinder& q = cylinders[i];
    bin(q.cx - q.r, q.cy - q.r, q.cx + q.r, q.cy + q.r, q.zt,
        static_cast<uint32_t>(i) | (kCylinder << 30));
  }
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const Sphere& q = spheres[i];
    bin(q.c.x - q.r, q.c.y - q.r, q.c.x + q.r, q.c.y + q.r, q.c.z + q.r,
        static_cast<uint32_t>(i) | (kSphere << 30));
  }
  prism_cs_.resize(2 * prisms.size());
  for (std::size_t i = 0; i < prisms.size(); ++i) {
    prism_cs_[2 * i] = std::cos(prisms[i].yaw);
    prism_cs_[2 * i + 1] = std::sin(prisms[i].yaw);
  }
  if (surface.any()) {
    const float bound = static_cast<float>(surface.roughnessBound());
    for (Cell& c : cells_) c.zmax += bound;
    buildCrownLines();
  }
  refs_.clear();
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    cells_[k].first = static_cast<uint32_t>(refs_.size());
    cells_[k].count = static_cast<uint32_t>(bins[k].size());
    refs_.insert(refs_.end(), bins[k].begin(), bins[k].end());
  }
}

bool World::traceCell(const Ray& ray, const Cell& cell, int ix, int iy, double t_in, double t_out,
                      uint64_t ray_key, Hit& hit) const {
  bool any = false;
  // Ground: the cell's tangent plane at its centre (second-order error (h_xx dx^2 + h_yy dy^2)/2 at
  // the corners: < 1.5 cm for hills.ini with 5 m cells, below the range noise).
  // Entering a cell below its plane means hitting the step between two planes.
  const double xc = x0_ + (ix + 0.5) * cell_, yc = y0_ + (iy + 0.5) * cell_;
  const double a = ray.d.z - cell.gx * ray.d.x - cell.gy * ray.d.y;
  const double f0 = ray.o.z - cell.gz - cell.gx * (ray.o.x - xc) - cell.gy * (ray.o.y - yc);
  const double t_best = hit.valid ? hit.t : std::numeric_limits<double>::infinity();
  double tg = -1;
  if (surface.any()) {
    static const CrownLine kFlat{};
    const CrownLine& cl = crown_.empty() ? kFlat : crown_[static_cast<std::size_t>(iy) * nx_ + ix];
    tg = surface.roughness_m != 0 ? roughGroundHit(ray, cl, f0, a, t_in, t_out)
                                  : crownedGroundHit(ray, cl, f0, a, t_in, t_out, 0);
  } else if (t_in > 0 && f0 + a * t_in < 0) {
    tg = t_in;
  } else if (a < 0) {
    const double t = -f0 / a;
    if (t >= t_in && t <= t_out) tg = t;
  }
  if (tg > 0 && tg < t_best) {
    const double inv = 1.0 / std::sqrt(cell.gx * cell.gx + cell.gy * cell.gy + 1.0);
    hit = Hit{tg, {-cell.gx * inv, -cell.gy * inv, inv}, cell.ground_material, true};
    any = true;
  }
  for (uint32_t k = cell.first; k < cell.first + cell.count; ++k) {
    const uint32_t ref = refs_[k], idx = ref & kIndexMask;
    switch (ref >> 30) {
      case kPrism:
        any |= intersect(ray, prisms[idx], prism_cs_[2 * idx], prism_cs_[2 * idx + 1], 1e-6, hit);
        break;
      case kCylinder: any |= intersect(ray, cylinders[idx], 1e-6, hit); break;
      default: {
        const Sphere& s = spheres[idx];
        double ti, to;
        if (!intersectSphere(ray, s, 1e-6, ti, to) || (hit.valid && ti >= hit.t)) break;
        // Porous crown: the ray passes with probability `porosity`, else stops at a random depth
        // in the front half of the chord (leaves are hit before the crown's far side).
        const uint64_t key = mix64(ray_key ^ (0xC2B2AE3D27D4EB4Full * (idx + 1)));
        if (uniform01(key) < materialProps(s.material).porosity) break;
        const double t = ti + 0.5 * (to - ti) * uniform01(key + 1);
        if (hit.valid && t >= hit.t) break;
        hit = Hit{t, {-ray.d.x, -ray.d.y, -ray.d.z}, s.material, true};
        any = true;
      }
    }
  }
  return any;
}

bool World::raycast(const Ray& ray, double max_range, uint64_t ray_key, const Prism* dynamic,
                    std::size_t n_dynamic, Hit& hit) const {
  hit.valid = false;
  hit.dynamic = -1;
  for (std::size_t i = 0; i < n_dynamic; ++i) {
    if (intersect(ray, dynamic[i], 1e-6, hit)) hit.dynamic = static_cast<int>(i);
  }
  const double t_dynamic = hit.valid ? hit.t : -1.0;
  // static surfaces only replace the hit when strictly nearer: an unchanged range is still the car's
  auto done = [&] {
    if (hit.dynamic >= 0 && hit.t != t_dynamic) hit.dynamic = -1;
    return hit.valid && hit.t <= max_range;
  };
  double fx = (ray.o.x - x0_) / cell_, fy = (ray.o.y - y0_) / cell_;
  int ix = static_cast<int>(std::floor(fx)), iy = static_cast<int>(std::floor(fy));
  if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) return done();
  // Amanatides & Woo (1987) 2D grid traversal.
  const double inf = std::numeric_limits<double>::infinity();
  const int sx = ray.d.x > 0 ? 1 : -1, sy = ray.d.y > 0 ? 1 : -1;
  const double dtx = ray.d.x != 0 ? cell_ / std::abs(ray.d.x) : inf;
  const double dty = ray.d.y != 0 ? cell_ / std::abs(ray.d.y) : inf;
  double tmx = ray.d.x != 0 ? ((ix + (sx > 0)) * cell_ + x0_ - ray.o.x) / ray.d.x : inf;
  double tmy = ray.d.y != 0 ? ((iy + (sy > 0)) * cell_ + y0_ - ray.o.y) / ray.d.y : inf;
  double t_in = 0;
  while (true) {
    const double t_out = std::min({tmx, tmy, max_range});
    const Cell& cell = cells_[static_cast<std::size_t>(iy) * nx_ + ix];
    const double z_low = ray.o.z + ray.d.z * (ray.d.z > 0 ? t_in : t_out);
    if (z_low <= cell.zmax) traceCell(ray, cell, ix, iy, t_in, t_out, ray_key, hit);
    if (hit.valid && hit.t <= t_out) break;
    if (t_out >= max_range) break;
    if (tmx < tmy) {
      ix += sx;
      t_in = tmx;
      tmx += dtx;
    } else {
      iy += sy;
      t_in = tmy;
      tmy += dty;
    }
    if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) break;
  }
  return done();
}

void finalizeRoad(Road& road) {
  const auto& c = road.centerline;
  road.cum_m.assign(c.size() + (road.closed ? 1 : 0), 0.0);
  for (std::size_t i = 1; i < road.cum_m.size(); ++i) {
    const Vec2& a = c[i - 1];
    const Vec2& b = c[i % c.size()];
    road.cum_m[i] = road.cum_m[i - 1] + std::hypot(b.x - a.x, b.y - a.y);
  }
}

double roadLength(const Road& road) { return road.cum_m.empty() ? 0 : road.cum_m.back(); }

void pointAtArcLength(const Road& road, double s, Vec2& p, double& heading) {
  const auto& c = road.centerline;
  const double len = roadLength(road);
  if (road.closed) {
    s = std::fmod(s, len);
    if (s < 0) s += len;
  } else {
    s = std::clamp(s, 0.0, len);
  }
  auto it = std::upper_bound(road.cum_m.begin(), road.cum_m.end(), s);
  std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - road.cum_m.begin()));
  i = std::min(i, road.cum_m.size() - 1);
  const Vec2& a = c[i - 1];
  const Vec2& b = c[i % c.size()];
  const double seg = road.cum_m[i] - road.cum_m[i - 1];
  const double f = seg > 0 ? (s - road.cum_m[i - 1]) / seg : 0;
  p = {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y)};
  heading = std::atan2(b.y - a.y, b.x - a.x);
}

Prism World::carPrism(const MovingCar& car, double t_s) const {
  const CarPose q = carPose(car, t_s);
  Prism p;
  p.cx = q.x;
  p.cy = q.y;
  p.yaw = q.yaw;
  p.hu = 0.5 * car.length_m;
  p.hv = 0.5 * car.width_m;
  const Vec2 g = ground.gradient(q.x, q.y);  // the body follows the terrain
  p.su = g.x * std::cos(q.yaw) + g.y * std::sin(q.yaw);
  p.sv = -g.x * std::sin(q.yaw) + g.y * std::cos(q.yaw);
  p.zb = q.z + 0.25;  // ground clearance: low beams pass under the body
  p.zt = q.z + car.height_m;
  p.material = car.material;
  return p;
}

}  // namespace roadslam::sim

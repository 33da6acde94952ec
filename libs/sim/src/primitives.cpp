#include "roadslam/sim/primitives.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace roadslam::sim {

const MaterialProps& materialProps(Material m) {
  // Reflectivities are typical 905 nm values (asphalt ~0.1, concrete ~0.3-0.4, foliage ~0.4-0.5,
  // black car paint ~0.03); glass mostly transmits or reflects specularly, so it rarely returns.
  static const std::array<MaterialProps, static_cast<int>(Material::kCount)> table{{
      {0.10f, 0.00f, 0.0f},   // Asphalt
      {0.25f, 0.00f, 0.0f},   // Terrain
      {0.35f, 0.00f, 0.0f},   // Concrete
      {0.45f, 0.00f, 0.0f},   // Facade
      {0.08f, 0.85f, 0.0f},   // Glass
      {0.45f, 0.00f, 0.55f},  // Foliage
      {0.20f, 0.00f, 0.0f},   // Bark
      {1.50f, 0.00f, 0.0f},   // Metal (retro-reflective signs / poles)
      {0.50f, 0.00f, 0.0f},   // CarPaint
      {0.03f, 0.00f, 0.0f},   // DarkPaint
      {0.30f, 0.00f, 0.0f},   // TunnelWall
  }};
  return table[static_cast<int>(m)];
}

namespace {
struct Clip {
  double t0, t1;
  int face0 = -1;
};

// One half-space a*t <= b of a convex clip (Kay & Kajiya slabs).
inline bool clipHalfSpace(double a, double b, int face, Clip& c) {
  if (a > 0) {
    c.t1 = std::min(c.t1, b / a);
  } else if (a < 0) {
    const double t = b / a;
    if (t > c.t0) {
      c.t0 = t;
      c.face0 = face;
    }
  } else if (b < 0) {
    return false;
  }
  return c.t0 <= c.t1;
}
}  // namespace

bool intersect(const Ray& ray, const Prism& p, double t_min, Hit& hit) {
  return intersect(ray, p, std::cos(p.yaw), std::sin(p.yaw), t_min, hit);
}

bool intersect(const Ray& ray, const Prism& p, double c, double s, double t_min, Hit& hit) {
  const double ox = ray.o.x - p.cx, oy = ray.o.y - p.cy;
  const double ou = c * ox + s * oy, ov = -s * ox + c * oy;
  const double du = c * ray.d.x + s * ray.d.y, dv = -s * ray.d.x + c * ray.d.y;
  Clip k{-1e300, hit.valid ? hit.t : 1e300};
  if (!clipHalfSpace(du, p.hu - ou, 0, k) || !clipHalfSpace(-du, p.hu + ou, 1, k) ||
      !clipHalfSpace(dv, p.hv - ov, 2, k) || !clipHalfSpace(-dv, p.hv + ov, 3, k) ||
      !clipHalfSpace(-(ray.d.z - p.su * du - p.sv * dv), ray.o.z - p.su * ou - p.sv * ov - p.zb, 4, k) ||
      !clipHalfSpace(ray.d.z - p.su * du - p.sv * dv, p.zt + p.su * ou + p.sv * ov - ray.o.z, 5, k))
    return false;
  if (k.t0 <= t_min || k.face0 < 0) return false;  // behind, or origin inside the prism
  Vec3 n;
  switch (k.face0) {
    case 0: n = {c, s, 0}; break;
    case 1: n = {-c, -s, 0}; break;
    case 2: n = {-s, c, 0}; break;
    case 3: n = {s, -c, 0}; break;
    default: {
      // top/bottom planes z - su*u - sv*v = const: gradient (-su, -sv, 1) in (u, v, z), rotated
      // to the world; the bottom face looks the other way
      const double gx = -p.su * c + p.sv * s, gy = -p.su * s - p.sv * c;
      const double inv = (k.face0 == 4 ? -1.0 : 1.0) / std::sqrt(gx * gx + gy * gy + 1.0);
      n = {gx * inv, gy * inv, inv};
    }
  }
  hit = Hit{k.t0, n, p.material, true};
  return true;
}

bool intersect(const Ray& ray, const Cylinder& cy, double t_min, Hit& hit) {
  const double ox = ray.o.x - cy.cx, oy = ray.o.y - cy.cy;
  const double a = ray.d.x * ray.d.x + ray.d.y * ray.d.y;
  const double t_best = hit.valid ? hit.t : 1e300;
  double t = 1e300;
  Vec3 n;
  if (a > 1e-12) {
    const double b = ox * ray.d.x + oy * ray.d.y, cc = ox * ox + oy * oy - cy.r * cy.r;
    const double disc = b * b - a * cc;
    if (disc >= 0) {
      const double ts = (-b - std::sqrt(disc)) / a;
      const double z = ray.o.z + ts * ray.d.z;
      if (ts > t_min && z >= cy.zb && z <= cy.zt) {
        t = ts;
        n = {(ox + ts * ray.d.x) / cy.r, (oy + ts * ray.d.y) / cy.r, 0};
      }
    }
  }
  if (ray.d.z < 0) {  // top cap, seen from above
    const double tc = (cy.zt - ray.o.z) / ray.d.z;
    const double x = ox + tc * ray.d.x, y = oy + tc * ray.d.y;
    if (tc > t_min && tc < t && x * x + y * y <= cy.r * cy.r) {
      t = tc;
      n = {0, 0, 1};
    }
  }
  if (t >= t_best || t == 1e300) return false;
  hit = Hit{t, n, cy.material, true};
  return true;
}

bool intersectSphere(const Ray& ray, const Sphere& s, double t_min, double& t_in, double& t_out) {
  const double ox = ray.o.x - s.c.x, oy = ray.o.y - s.c.y, oz = ray.o.z - s.c.z;
  const double b = ox * ray.d.x + oy * ray.d.y + oz * ray.d.z;
  const double disc = b * b - (ox * ox + oy * oy + oz * oz - s.r * s.r);
  if (disc < 0) return false;
  const double q = std::sqrt(disc);
  t_in = -b - q;
  t_out = -b + q;
  return t_in > t_min;
}

void footprintBounds(const Prism& p, double& xmin, double& ymin, double& xmax, double& ymax) {
  const double c = std::abs(std::cos(p.yaw)), s = std::abs(std::sin(p.yaw));
  const double ex = c * p.hu + s * p.hv, ey = s * p.hu + c * p.hv;
  xmin = p.cx - ex;
  xmax = p.cx + ex;
  ymin = p.cy - ey;
  ymax = p.cy + ey;
}

double topMax(const Prism& p) { return p.zt + std::abs(p.su) * p.hu + std::abs(p.sv) * p.hv; }

}  // namespace roadslam::sim

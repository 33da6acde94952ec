// Ray caster against analytic geometry, and the grid traversal against brute force.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/sim/primitives.h"
#include "roadslam/sim/world.h"
#include "roadslam/sim/world_builder.h"

using namespace roadslam::sim;

namespace {
Ray ray(Vec3 o, Vec3 d) {
  const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return {o, {d.x / n, d.y / n, d.z / n}};
}
World flatWorld() {
  World w;
  w.buildGrid(-50, -50, 50, 50, 5);
  return w;
}
}  // namespace

TEST(RayCast, RayToGroundPlane) {
  const World w = flatWorld();
  Hit h;
  ASSERT_TRUE(w.raycast(ray({1, 2, 2}, {1, 0, -1}), 100, 0, nullptr, 0, h));
  EXPECT_NEAR(h.t, 2 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(h.n.z, 1.0, 1e-12);
  EXPECT_FALSE(w.raycast(ray({1, 2, 2}, {1, 0, 0.01}), 100, 0, nullptr, 0, h)) << "sky gives nothing";
  EXPECT_FALSE(w.raycast(ray({1, 2, 2}, {1, 0, -0.01}), 100, 0, nullptr, 0, h)) << "beyond max range";
}

// Each 5 m cell uses the tangent plane at its centre: the error bound is the second-order Taylor
// term (|h_xx| dx^2 + |h_yy| dy^2) / 2 at the cell corner (dx = dy = 2.5 m), 1.5 cm here.
TEST(RayCast, HillsGroundWithinTheTangentPlaneBound) {
  World w;
  w.ground.amplitude_m = 6;
  w.ground.wavelength_m = 300;
  w.buildGrid(-150, -150, 150, 150, 5);
  const double k = 2 * M_PI / 300, hxx = 6 * k * k, hyy = 0.5 * 6 * k * k / 0.64;
  const double bound = (hxx + hyy) * 2.5 * 2.5 / 2;
  Rng rng{42};
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const double x = rng.uniform(-50, 50), y = rng.uniform(-50, 50);
    const Vec3 o{x, y, w.ground.height(x, y) + 1.9};
    const double az = rng.uniform(0, 6.283), el = rng.uniform(-0.26, -0.02);
    const Ray r = ray(o, {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
    Hit h;
    if (!w.raycast(r, 100, 0, nullptr, 0, h)) continue;
    ++hits;
    const double px = o.x + h.t * r.d.x, py = o.y + h.t * r.d.y, pz = o.z + h.t * r.d.z;
    ASSERT_NEAR(pz, w.ground.height(px, py), bound) << "ray " << i;
  }
  EXPECT_GT(hits, 1500);
}

TEST(RayCast, AxisAlignedAndRotatedBox) {
  Prism b;
  b.cx = 10; b.cy = 0; b.hu = 1; b.hv = 2; b.zb = 0; b.zt = 3;
  Hit h;
  ASSERT_TRUE(intersect(ray({0, 0, 1}, {1, 0, 0}), b, 1e-9, h));
  EXPECT_NEAR(h.t, 9, 1e-12);
  EXPECT_NEAR(h.n.x, -1, 1e-12);
  h = {};
  ASSERT_TRUE(intersect(ray({10, 0, 10}, {0, 0, -1}), b, 1e-9, h));
  EXPECT_NEAR(h.t, 7, 1e-12);  // top face
  EXPECT_NEAR(h.n.z, 1, 1e-12);
  h = {};
  EXPECT_FALSE(intersect(ray({0, 0, 3.5}, {1, 0, 0}), b, 1e-9, h));
  EXPECT_FALSE(intersect(ray({10, 0, 1}, {1, 0, 0}), b, 1e-9, h)) << "origin inside";
  // Rotated by 45 deg: the corner at x = 10 - sqrt(2)... reference: the face u = -hu along the ray.
  b.yaw = M_PI / 4;
  b.hv = 1;
  h = {};
  ASSERT_TRUE(intersect(ray({0, 0, 1}, {1, 0, 0}), b, 1e-9, h));
  EXPECT_NEAR(h.t, 10 - std::sqrt(2.0), 1e-9);
}

TEST(RayCast, SlopedTopPrismAgainstMarchingReference) {
  Prism p;
  p.cx = 3; p.cy = -2; p.yaw = 0.7; p.hu = 2; p.hv = 1.5; p.zb = -1; p.zt = 0.5; p.su = 0.1; p.sv = -0.05;
  auto inside = [&](double x, double y, double z) {
    const double c = std::cos(p.yaw), s = std::sin(p.yaw);
    const double u = c * (x - p.cx) + s * (y - p.cy), v = -s * (x - p.cx) + c * (y - p.cy);
    return std::abs(u) <= p.hu && std::abs(v) <= p.hv && z >= p.zb + p.su * u + p.sv * v &&
           z <= p.zt + p.su * u + p.sv * v;
  };
  Rng rng{7};
  int hits = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 o{rng.uniform(-10, -3), rng.uniform(-8, 4), rng.uniform(0.5, 4)};
    const Ray r = ray(o, {3 - o.x + rng.uniform(-3, 3), -2 - o.y + rng.uniform(-3, 3), rng.uniform(-4, 0)});
    double t_ref = -1;
    for (double t = 0; t < 40; t += 1e-3)
      if (inside(o.x + t * r.d.x, o.y + t * r.d.y, o.z + t * r.d.z)) { t_ref = t; break; }
    Hit h;
    const bool hit = intersect(r, p, 1e-9, h);
    ASSERT_EQ(hit, t_ref >= 0) << "ray " << i;
    if (hit) {
      ++hits;
      EXPECT_NEAR(h.t, t_ref, 1.5e-3);
    }
  }
  EXPECT_GT(hits, 100);
}

TEST(RayCast, VerticalCylinder) {
  const Cylinder c{5, 0, 0.5, 0, 4, Material::Metal};
  Hit h;
  ASSERT_TRUE(intersect(ray({0, 0, 1}, {1, 0, 0}), c, 1e-9, h));
  EXPECT_NEAR(h.t, 4.5, 1e-12);
  h = {};
  ASSERT_TRUE(intersect(ray({0, 0.3, 1}, {1, 0, 0}), c, 1e-9, h));
  EXPECT_NEAR(h.t, 5 - 0.4, 1e-12);  // sqrt(0.5^2 - 0.3^2) = 0.4
  EXPECT_NEAR(h.n.x, -0.8, 1e-12);
  h = {};
  EXPECT_FALSE(intersect(ray({0, 0, 4.5}, {1, 0, 0}), c, 1e-9, h)) << "above the top";
  EXPECT_FALSE(intersect(ray({0, 0.6, 1}, {1, 0, 0}), c, 1e-9, h)) << "beside";
  ASSERT_TRUE(intersect(ray({5, 0.1, 10}, {0, 0, -1}), c, 1e-9, h));
  EXPECT_NEAR(h.t, 6, 1e-12);  // top cap
}

TEST(RayCast, Sphere) {
  const Sphere s{{10, 0, 2}, 1.5, Material::Foliage};
  double ti, to;
  ASSERT_TRUE(intersectSphere(ray({0, 0, 2}, {1, 0, 0}), s, 1e-9, ti, to));
  EXPECT_NEAR(ti, 8.5, 1e-12);
  EXPECT_NEAR(to, 11.5, 1e-12);
  EXPECT_FALSE(intersectSphere(ray({0, 0, 3.6}, {1, 0, 0}), s, 1e-9, ti, to));
}

// The 2D grid traversal must find exactly the closest surface a brute-force scan over every
// primitive finds (flat ground so the reference can intersect z = 0 exactly; no porous crowns).
TEST(RayCast, GridTraversalEqualsBruteForce) {
  WorldParams p;
  p.length_m = 200;
  p.width_m = 120;
  Road route;
  World w = buildWorld(p, 11, route);
  w.spheres.clear();
  w.buildGrid(w.xmin(), w.ymin(), w.xmax(), w.ymax(), p.grid_cell_m);
  ASSERT_GT(w.prisms.size(), 100u);
  Rng rng{3};
  int hits = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec2 q = route.centerline[static_cast<std::size_t>(rng.uniform(0, route.centerline.size() - 1))];
    const Vec3 o{q.x, q.y, 1.9};
    const double az = rng.uniform(0, 6.283), el = rng.uniform(-0.26, 0.26);
    const Ray r = ray(o, {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)});
    Hit ref;
    if (r.d.z < 0) ref = Hit{-o.z / r.d.z, {0, 0, 1}, Material::Terrain, true};
    for (const Prism& pr : w.prisms) intersect(r, pr, 1e-6, ref);
    for (const Cylinder& c : w.cylinders) intersect(r, c, 1e-6, ref);
    const bool ref_ok = ref.valid && ref.t <= 100;
    Hit h;
    ASSERT_EQ(w.raycast(r, 100, 0, nullptr, 0, h), ref_ok) << "ray " << i;
    if (ref_ok) {
      ++hits;
      ASSERT_NEAR(h.t, ref.t, 1e-9) << "ray " << i;
    }
  }
  EXPECT_GT(hits, 2000);
}

// Oracle for boundary work: the ground-truth curb polylines lie on the curb faces the sensor sees.
// A horizontal ray cast from 1 m inside the road, at half the curb height, towards each curb
// segment's midpoint hits concrete 1 m away (straight pieces stand off curves by <= 2 cm).
TEST(RayCast, GroundTruthCurbsLieOnTheCurbFaces) {
  for (const bool hills : {false, true}) {
    WorldParams p;
    if (hills) {
      p.hill_amplitude_m = 6;
      p.hill_wavelength_m = 300;
    }
    Road route;
    const World w = buildWorld(p, 5, route);
    std::size_t n = 0;
    double worst = 0;
    for (const Road& r : w.roads)
      for (int side : {+1, -1})
        for (const auto& line : side > 0 ? r.left_curbs : r.right_curbs)
          for (std::size_t i = 1; i < line.size(); ++i) {
            const Vec2 a = line[i - 1], b = line[i];
            const double len = std::hypot(b.x - a.x, b.y - a.y);
            // left curbs have the road on their right (inward = -left normal), right curbs on their left
            const Vec2 in{side * (b.y - a.y) / len, -side * (b.x - a.x) / len};
            const Vec2 m{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
            // aim along the terrain: from 1 m inside the road to the curb point, both at half curb height
            const Vec3 o{m.x + in.x, m.y + in.y, w.ground.height(m.x + in.x, m.y + in.y) + 0.5 * p.curb_height_m};
            const Vec3 target{m.x, m.y, w.ground.height(m.x, m.y) + 0.5 * p.curb_height_m};
            const Vec3 d{target.x - o.x, target.y - o.y, target.z - o.z};
            const double dist = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
            Hit h;
            ASSERT_TRUE(w.raycast(ray(o, d), 10, 0, nullptr, 0, h)) << r.name << " " << i;
            EXPECT_EQ(h.material, Material::Concrete) << r.name << " " << i << " hills " << hills;
            if (std::abs(h.t - dist) > 0.03)
              ADD_FAILURE() << r.name << " curb segment " << i << " at " << m.x << ", " << m.y << ": hit at "
                            << h.t << " m instead of " << dist << " m";
            worst = std::max(worst, std::abs(h.t - dist));
            ++n;
          }
    EXPECT_GT(n, 300u);
    EXPECT_LT(worst, 0.03) << (hills ? "hills" : "flat");
  }
}

#pragma once
/// \file primitives.h
/// Analytic primitives of the simulated world and their exact ray intersections. All coordinates
/// are in the world frame (x east, y north, z up) in metres; ray directions are unit vectors, so the
/// ray parameter t is a range in metres.

#include <cstdint>

namespace roadslam::sim {

struct Vec3 {
  double x = 0, y = 0, z = 0;
};

/// Surface materials: reflectivity drives intensity and the detection of dark surfaces.
enum class Material : uint8_t {
  Asphalt, Terrain, Concrete, Facade, Glass, Foliage, Bark, Metal, CarPaint, DarkPaint, TunnelWall,
  kCount
};

struct MaterialProps {
  float reflectivity;  ///< diffuse reflectivity [0..1]; > 1 for retro-reflectors
  float dropout;       ///< extra probability that a return is lost on this material [0..1]
  float porosity;      ///< probability a ray passes through (foliage) [0..1]
};
const MaterialProps& materialProps(Material m);

struct Ray {
  Vec3 o;  ///< origin in the world frame [m]
  Vec3 d;  ///< unit direction in the world frame
};

/// Closest intersection found so far; t = range along the ray [m].
struct Hit {
  double t = 0;
  Vec3 n;  ///< unit surface normal at the hit (world frame)
  Material material = Material::Terrain;
  bool valid = false;
  int dynamic = -1;  ///< World::raycast: index of the dynamic prism (moving car) hit, -1 a static surface
};

/// A prism on an oriented rectangle: footprint centred at (cx, cy) with heading yaw [rad] and half
/// extents hu (along) / hv (across) [m]; top and bottom are the parallel planes z = zt + su*u + sv*v
/// and z = zb + su*u + sv*v in the prism's local (u, v) coordinates [m] (slopes follow the terrain:
/// sidewalks, cars and tunnel ceilings on hills).
/// Boxes, buildings, facade bands, curbs/sidewalks, cars and tunnel walls are all prisms.
struct Prism {
  double cx = 0, cy = 0, yaw = 0, hu = 0.5, hv = 0.5, zb = 0, zt = 1, su = 0, sv = 0;
  Material material = Material::Concrete;
};

/// A vertical cylinder (pole, trunk): axis at (cx, cy), radius r, from zb to zt [m].
struct Cylinder {
  double cx = 0, cy = 0, r = 0.1, zb = 0, zt = 1;
  Material material = Material::Metal;
};

/// A sphere (tree crown), centre c and radius r [m].
struct Sphere {
  Vec3 c;
  double r = 1;
  Material material = Material::Foliage;
};

/// Exact intersections: update \p hit and return true when the primitive is hit at
/// t in (t_min, hit.t) (or any t > t_min when hit.valid is false). Rays starting inside a solid
/// primitive see no hit from it.
bool intersect(const Ray& ray, const Prism& p, double t_min, Hit& hit);
/// Same with the prism's cos(yaw), sin(yaw) precomputed (the ray caster's hot path).
bool intersect(const Ray& ray, const Prism& p, double cos_yaw, double sin_yaw, double t_min, Hit& hit);
bool intersect(const Ray& ray, const Cylinder& c, double t_min, Hit& hit);
/// Entry and exit ranges of the ray through the sphere; false when it misses or is behind.
bool intersectSphere(const Ray& ray, const Sphere& s, double t_min, double& t_in, double& t_out);

/// Axis-aligned footprint bounds of a prism [m].
void footprintBounds(const Prism& p, double& xmin, double& ymin, double& xmax, double& ymax);
/// Highest point of a prism's top [m].
double topMax(const Prism& p);

}  // namespace roadslam::sim

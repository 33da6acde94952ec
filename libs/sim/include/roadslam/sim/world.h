#pragma once
/// \file world.h
/// The simulated road world: a smooth height-field ground, analytic primitives (prisms, cylinders,
/// porous spheres) indexed by a 2D uniform grid, roads with their curb lines, and moving cars.
/// World frame: x east, y north, z up [m]. Built by buildWorld() (world_builder.h).

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/sim/primitives.h"

namespace roadslam::sim {

struct Vec2 {
  double x = 0, y = 0;
};

/// Smooth hills: h(x, y) = A sin(2 pi x / L) + A/2 sin(2 pi y / (0.8 L)) [m]; flat when A = 0.
struct Ground {
  double amplitude_m = 0;     ///< A [m]
  double wavelength_m = 400;  ///< L [m]
  double height(double x, double y) const;
  /// Gradient (dh/dx, dh/dy) [m/m].
  Vec2 gradient(double x, double y) const;
};

/// Small-scale road surface on top of Ground (both off when 0): a crowned carriageway (cross slope
/// falling from the centreline to the curbs, so the road edges, sidewalks and terrain keep the
/// Ground height) and a deterministic roughness height field (a sum of seeded plane waves).
struct RoadSurface {
  double cross_slope = 0;       ///< crown: height slope across the carriageway [m/m]
  double roughness_m = 0;       ///< standard deviation of the roughness height [m]
  double roughness_wavelength_m = 1.0;  ///< central wavelength of the roughness [m]
  static constexpr int kWaves = 4;
  double wave_kx[kWaves] = {}, wave_ky[kWaves] = {}, wave_phase[kWaves] = {};  ///< [rad/m, rad]
  double wave_amplitude_m = 0;  ///< amplitude of each wave: roughness_m * sqrt(2 / kWaves) [m]
  /// Draws the waves from \p seed (directions uniform, wavelengths 0.5..2 x the central one).
  void seedWaves(uint64_t seed);
  /// Roughness height at (x, y) [m]; 0 when roughness_m = 0.
  double roughness(double x, double y) const;
  /// Bound on |roughness| [m].
  double roughnessBound() const { return kWaves * wave_amplitude_m; }
  bool any() const { return cross_slope != 0 || roughness_m != 0; }
};

/// A road: dense centreline (about 0.5 m spacing) and the curb lines where sidewalks exist.
struct Road {
  std::string name;
  std::vector<Vec2> centerline;  ///< world frame [m]
  std::vector<double> cum_m;     ///< arc length at each centreline point [m] (see finalizeRoad())
  double half_width_m = 3.5;     ///< centreline to curb face [m]
  bool closed = false;           ///< loop: last point connects to the first
  /// Curb polylines (road edge at the curb face) [m]; several pieces where intersections cut them.
  std::vector<std::vector<Vec2>> left_curbs, right_curbs;
};

/// A car driving along a road (a moving occluder): at constant speed, or on a planned lap
/// (World::planTraffic) followed behind the car ahead (World::followTraffic).
struct MovingCar {
  int road = 0;            ///< index into World::roads
  double s0_m = 0;         ///< arc length along the centreline at t = 0 [m]
  double speed_mps = 10;   ///< signed: negative drives against the centreline direction [m/s]
  double lateral_m = 1.75;  ///< offset to the right of the travel direction (right-hand traffic) [m]
  double length_m = 4.5, width_m = 1.8, height_m = 1.5;  ///< [m]
  Material material = Material::CarPaint;
  /// Its lap planned by World::planTraffic: the time [s] at which it passes each of lap_s.size()
  /// evenly spaced arc lengths of its lap (lap_t[0] = 0, the last = the lap's period). Empty: it
  /// drives at speed_mps everywhere, corners included.
  std::vector<double> lap_t;
  /// The planned speed along its own path at each of those arc lengths but the last [m/s]
  /// (World::planTraffic; the lap is periodic).
  std::vector<double> lap_v;
  /// Its drive among the others (World::followTraffic): how far its lap coordinate has run along its
  /// travel direction since t = 0 at every World::kFollowStep_s [m, unwrapped]. Empty: lap_t alone.
  std::vector<double> follow_u;
};

/// Car-following of planned traffic (World::followTraffic): the Intelligent Driver Model (IDM; Treiber,
/// Hennecke & Helbing, Phys. Rev. E 62, 1805, 2000) with the planned, curve-limited speed as the
/// desired speed.
struct FollowParams {
  double span_s = 0;          ///< integrated over [0, span_s]; <= 0: no following [s]
  double headway_s = 1.5;     ///< T, safe time headway [s]
  double min_gap_m = 2.0;     ///< s0, bumper-to-bumper gap standing [m]
  double accel_mps2 = 2.0;    ///< a, maximum acceleration [m/s^2]
  double decel_mps2 = 2.0;    ///< b, comfortable deceleration [m/s^2]
};

/// Pose of a moving car at time t: centre (x, y), ground z and heading [m, rad].
struct CarPose {
  double x = 0, y = 0, z = 0, yaw = 0;
};

class World {
 public:
  Ground ground;
  RoadSurface surface;
  std::vector<Prism> prisms;
  std::vector<Cylinder> cylinders;
  std::vector<Sphere> spheres;
  std::vector<Road> roads;
  std::vector<MovingCar> cars;
  double ground_margin_m = 0;  ///< informational: the grid covers the content plus this margin [m]

  /// Builds the acceleration grid over [xmin, xmax] x [ymin, ymax] with square cells [m].
  /// Must be called after the primitives are final and before raycast().
  void buildGrid(double xmin, double ymin, double xmax, double ymax, double cell_m);

  /// Closest surface along \p ray within (0, max_range] [m] among the ground, the static primitives
  /// and the \p dynamic prisms (moving cars at the firing time). \p ray_key seeds the deterministic
  /// draw that decides where a ray stops inside porous foliage. Allocation-free.
  bool raycast(const Ray& ray, double max_range, uint64_t ray_key, const Prism* dynamic,
               std::size_t n_dynamic, Hit& hit) const;

  /// Height of the crown and roughness above Ground::height at (x, y) [m] (0 when RoadSurface is
  /// off or outside the grid); the crown uses the nearest road of the grid cell.
  double surfaceOffset(double x, double y) const;
  /// The crown alone [m]: what the car's body rides on. Roughness of ~1 m wavelength reaches the
  /// wheels at 10+ Hz, far above a car's 1-1.5 Hz body modes, so the suspension keeps it from the
  /// body (Gillespie, Fundamentals of Vehicle Dynamics, 1992, ch. 5: ride isolation).
  double crownOffset(double x, double y) const;
  /// Ground::height + surfaceOffset: the surface the ray caster sees and the car drives on [m].
  double surfaceHeight(double x, double y) const { return ground.height(x, y) + surfaceOffset(x, y); }

  /// Car pose at time \p t_s [s] (cars wrap around at the end of a road): from follow_u when it is
  /// filled, else from lap_t, else at speed_mps.
  CarPose carPose(const MovingCar& car, double t_s) const;
  /// Plans every car's lap: its speed is |speed_mps| on the straights and at most sqrt(a_lat / |k|) on
  /// its own path's curvature k, reached and left at \p accel_mps2 (braking and accelerating alike, so
  /// the plan holds both ways along a road). \p lateral_accel_mps2 <= 0: constant speeds.
  void planTraffic(double lateral_accel_mps2, double accel_mps2);
  /// Drives the planned cars (those with a lap_t) jointly so that none drives into the car ahead in its
  /// lane (same road, direction and lateral_m): fills every planned car's follow_u. A car closer at
  /// t = 0 to one of the cars placed before it (lower index) than the IDM's desired gap is moved back,
  /// behind that car, to that gap (its s0_m changes). Throws naming [world] moving_cars when a lane
  /// cannot hold its cars.
  void followTraffic(const FollowParams& f);
  static constexpr double kFollowStep_s = 0.01;  ///< integration step of followTraffic [s]
  /// The car as a prism at time \p t_s.
  Prism carPrism(const MovingCar& car, double t_s) const;

  double xmin() const { return x0_; }
  double ymin() const { return y0_; }
  double xmax() const { return x0_ + nx_ * cell_; }
  double ymax() const { return y0_ + ny_ * cell_; }

 private:
  struct Cell {
    double gz = 0, gx = 0, gy = 0;  ///< ground plane: z = gz + gx (x - xc) + gy (y - yc) [m]
    float zmax = 0;                 ///< highest surface in the cell [m]
    Material ground_material = Material::Terrain;
    uint32_t first = 0, count = 0;  ///< range in refs_
  };
  /// The nearest road of a cell, for the crown: centreline point, unit direction, half width [m].
  struct CrownLine {
    double px = 0, py = 0, dx = 1, dy = 0, hw = 0;  ///< hw = 0: no road near this cell
  };
  bool traceCell(const Ray& ray, const Cell& cell, int ix, int iy, double t_in, double t_out,
                 uint64_t ray_key, Hit& hit) const;
  /// First crossing of the ray under the cell's detailed surface (plane + crown + \p offset) within
  /// [t_in, t_out]; < 0 when none. \p f0, \p a: the ray's height above the plane, f0 + a t.
  double crownedGroundHit(const Ray& ray, const CrownLine& cl, double f0, double a, double t_in,
                          double t_out, double offset) const;
  /// Same on plane + crown + roughness (a march and bisection: the roughness is not linear).
  double roughGroundHit(const Ray& ray, const CrownLine& cl, double f0, double a, double t_in,
                        double t_out) const;
  void buildCrownLines();
  std::vector<CrownLine> crown_;  ///< per cell, when surface.cross_slope != 0

  double x0_ = 0, y0_ = 0, cell_ = 5;
  int nx_ = 0, ny_ = 0;
  std::vector<Cell> cells_;
  std::vector<double> prism_cs_;  ///< cos(yaw), sin(yaw) of every prism
  std::vector<uint32_t> refs_;  ///< 2 high bits: 0 prism, 1 cylinder, 2 sphere; low 30 bits: index
};

/// Fills Road::cum_m (for a closed road the last entry is the length back to the first point).
void finalizeRoad(Road& road);
/// Total length of a finalized road [m].
double roadLength(const Road& road);
/// Position and heading [m, rad] at arc length \p s [m] on a finalized road (wrapped when closed,
/// clamped when open).
void pointAtArcLength(const Road& road, double s, Vec2& p, double& heading);

/// splitmix64: the deterministic, counter-based random source of the simulator.
inline uint64_t mix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
/// Uniform in [0, 1) from a 64-bit key.
inline double uniform01(uint64_t key) { return static_cast<double>(mix64(key) >> 11) * 0x1.0p-53; }

/// A sequential deterministic generator (same numbers on every platform, unlike std distributions).
struct Rng {
  uint64_t state;
  double uniform(double a = 0, double b = 1) { return a + (b - a) * uniform01(state++); }
  /// Standard normal (Box-Muller).
  double normal() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }
};

}  // namespace roadslam::sim

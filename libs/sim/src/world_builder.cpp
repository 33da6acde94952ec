// Road layouts, curbs/sidewalks and the tunnel; roadside objects are in roadside.cpp.
#include "roadslam/sim/world_builder.h"

#include <algorithm>
#include <cmath>

#include "roadside.h"

namespace roadslam::sim {

namespace {
constexpr double kPi = 3.141592653589793;

Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }

void appendLine(std::vector<Vec2>& out, Vec2 a, Vec2 b, double step) {
  const int n = std::max(1, static_cast<int>(std::ceil(norm(sub(b, a)) / step)));
  for (int i = 0; i < n; ++i) out.push_back({a.x + (b.x - a.x) * i / n, a.y + (b.y - a.y) * i / n});
}

Road makeRoad(std::string name, std::vector<Vec2> wps, bool closed, const WorldParams& p) {
  Road r;
  r.name = std::move(name);
  r.closed = closed;
  r.half_width_m = p.lanes_per_side * p.lane_width_m + p.parking_width_m;
  r.centerline = filletPolyline(wps, closed, p.corner_radius_m, 0.5);
  finalizeRoad(r);
  return r;
}

/// Roads and the route's waypoints for each layout.
void makeLayout(const WorldParams& p, std::vector<Road>& roads, std::vector<Vec2>& route_wps,
                bool& route_closed) {
  const double L = p.length_m, W = p.width_m;
  if (p.layout == "loop") {
    route_wps = {{0.1 * L, 0}, {L, 0}, {L, W}, {0, W}, {0, 0}};
    route_closed = true;
    roads.push_back(makeRoad("loop", route_wps, true, p));
  } else if (p.layout == "straight") {
    const int n = std::max(2, static_cast<int>(L / 250.0));
    for (int i = 0; i <= n; ++i)
      route_wps.push_back({L * i / n, (i == 0 || i == n) ? 0 : p.curviness_m * std::sin(1.7 * i)});
    route_closed = false;
    roads.push_back(makeRoad("main", route_wps, false, p));
  } else {  // grid: parallel streets joined by two cross streets, serpentine route
    const int n = p.streets;
    for (int k = 0; k < n; ++k)
      roads.push_back(makeRoad("street_" + std::to_string(k), {{0, k * W}, {L, k * W}}, false, p));
    roads.push_back(makeRoad("cross_west", {{0, 0}, {0, (n - 1) * W}}, false, p));
    roads.push_back(makeRoad("cross_east", {{L, 0}, {L, (n - 1) * W}}, false, p));
    route_wps.push_back({0.1 * L, 0});
    for (int k = 0; k < n; ++k) {
      const bool east = (k % 2) == 0;
      if (k > 0) route_wps.push_back({east ? 0 : L, k * W});
      route_wps.push_back({east ? L : 0, k * W});
    }
    route_closed = (n % 2) == 0;  // an even count ends on the west cross street
    if (route_closed) route_wps.push_back({0, 0});
  }
}

/// Offsets a dense polyline to the right of its direction by \p d [m].
std::vector<Vec2> offsetRight(const std::vector<Vec2>& line, bool closed, double d) {
  std::vector<Vec2> out(line.size());
  const std::size_t n = line.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = (i > 0) ? line[i - 1] : (closed ? line[n - 1] : line[i]);
    const Vec2 b = (i + 1 < n) ? line[i + 1] : (closed ? line[0] : line[i]);
    const double h = std::atan2(b.y - a.y, b.x - a.x);
    out[i] = {line[i].x + d * std::sin(h), line[i].y - d * std::cos(h)};
  }
  return out;
}
}  // namespace

std::vector<Vec2> filletPolyline(const std::vector<Vec2>& w, bool closed, double radius,
                                 double step) {
  const std::size_t n = w.size();
  std::vector<Vec2> out;
  if (n < 2) return w;
  // Tangent points (t_in, t_out) of every corner; open ends are their own tangent points.
  std::vector<Vec2> t_in(n), t_out(n);
  std::vector<double> r_eff(n, 0.0);
  std::vector<Vec2> centre(n);
  std::vector<int> turn(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    t_in[i] = t_out[i] = w[i];
    if (!closed && (i == 0 || i + 1 == n)) continue;
    const Vec2 a = w[(i + n - 1) % n], p = w[i], b = w[(i + 1) % n];
    const Vec2 u1 = sub(p, a), u2 = sub(b, p);
    const double l1 = norm(u1), l2 = norm(u2);
    const double cross = u1.x * u2.y - u1.y * u2.x, dot = u1.x * u2.x + u1.y * u2.y;
    const double theta = std::atan2(std::abs(cross), dot);  // turn angle
    if (theta < 1e-6) continue;
    double d = radius * std::tan(theta / 2);
    d = std::min(d, 0.45 * std::min(l1, l2));
    r_eff[i] = d / std::tan(theta / 2);
    turn[i] = cross > 0 ? 1 : -1;
    t_in[i] = {p.x - u1.x / l1 * d, p.y - u1.y / l1 * d};
    t_out[i] = {p.x + u2.x / l2 * d, p.y + u2.y / l2 * d};
    // centre on the inner side of the turn: left normal of u1 for a left turn
    centre[i] = {t_in[i].x - turn[i] * u1.y / l1 * r_eff[i], t_in[i].y + turn[i] * u1.x / l1 * r_eff[i]};
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (turn[i] != 0) {
      const double a0 = std::atan2(t_in[i].y - centre[i].y, t_in[i].x - centre[i].x);
      double a1 = std::atan2(t_out[i].y - centre[i].y, t_out[i].x - centre[i].x);
      double da = a1 - a0;
      while (turn[i] > 0 && da < 0) da += 2 * kPi;
      while (turn[i] < 0 && da > 0) da -= 2 * kPi;
      const int m = std::max(1, static_cast<int>(std::ceil(std::abs(da) * r_eff[i] / step)));
      for (int k = 0; k < m; ++k) {
        const double a = a0 + da * k / m;
        out.push_back({centre[i].x + r_eff[i] * std::cos(a), centre[i].y + r_eff[i] * std::sin(a)});
      }
    }
    if (i + 1 < n || closed) appendLine(out, t_out[i], t_in[(i + 1) % n], step);
  }
  if (!closed) out.push_back(w[n - 1]);
  return out;
}

World buildWorld(const WorldParams& p, uint64_t seed, Road& route) {
  World world;
  world.ground.amplitude_m = p.hill_amplitude_m;
  world.ground.wavelength_m = p.hill_wavelength_m;
  std::vector<Vec2> wps;
  bool closed = false;
  makeLayout(p, world.roads, wps, closed);
  route = Road{};
  route.name = "route";
  route.closed = closed;
  route.half_width_m = 0.5 * p.lane_width_m;
  route.centerline =
      offsetRight(filletPolyline(wps, closed, p.corner_radius_m, 0.5), closed, 0.5 * p.lane_width_m);
  finalizeRoad(route);

  Rng rng{mix64(seed ^ 0x5EEDF00Dull)};
  const RoadIndex index(world.roads);
  addSidewalks(p, index, world);
  addTunnel(p, world);
  addRoadsideObjects(p, index, rng, world);
  if (p.traffic_seed < 0) {
    addMovingCars(p, rng, world);
  } else {
    Rng traffic{mix64(static_cast<uint64_t>(p.traffic_seed) ^ 0x7AFF1C5EEDull)};
    addMovingCars(p, traffic, world);
  }
  world.planTraffic(p.moving_car_lateral_accel_mps2, p.moving_car_accel_mps2);

  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const Road& r : world.roads)
    for (const Vec2& q : r.centerline) {
      xmin = std::min(xmin, q.x);
      ymin = std::min(ymin, q.y);
      xmax = std::max(xmax, q.x);
      ymax = std::max(ymax, q.y);
    }
  world.surface.cross_slope = p.road_cross_slope;
  world.surface.roughness_m = p.road_roughness_m;
  world.surface.roughness_wavelength_m = p.road_roughness_wavelength_m;
  world.surface.seedWaves(seed);
  world.ground_margin_m = p.margin_m;
  world.buildGrid(xmin - p.margin_m, ymin - p.margin_m, xmax + p.margin_m, ymax + p.margin_m,
                  p.grid_cell_m);
  return world;
}

}  // namespace roadslam::sim

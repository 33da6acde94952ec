// Car-following of the planned traffic (World::followTraffic): the Intelligent Driver Model
// integrated for all the cars of a lane jointly, at a fixed step, over the drive's span.
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "traffic.h"

namespace roadslam::sim {

namespace {

/// A lane's path in travel order: the lap samples u_j = j lap / n of World::planTraffic, taken
/// along the travel direction, with the path length (the cars' own, offset from the centreline) to
/// each.
struct LanePath {
  int dir = 1;            ///< +1 along the centreline, -1 against it
  double lap = 0;         ///< lap coordinate range [m]
  std::size_t n = 0;      ///< samples per lap
  std::vector<double> q;  ///< path length at travel sample i = 0..n (q[n]: the whole lap) [m]

  double length() const { return q.back(); }
  double wrap(double x) const {
    const double w = std::fmod(x, length());
    return w < 0 ? w + length() : w;
  }
  /// Fractional travel sample at path length \p x [m].
  double index(double x) const {
    x = wrap(x);
    const auto k = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(std::upper_bound(q.begin(), q.end(), x) - q.begin() - 1, 0,
                                   static_cast<std::ptrdiff_t>(n) - 1));
    const double d = q[k + 1] - q[k];
    return static_cast<double>(k) + (d > 0 ? (x - q[k]) / d : 0.0);
  }
  /// Lap coordinate run along the travel direction from path length 0 to the unwrapped \p x [m].
  double travelU(double x) const {
    const double laps = std::floor(x / length());
    return laps * lap + index(x - laps * length()) * lap / static_cast<double>(n);
  }
  /// Path length of the lap coordinate \p u (in [0, lap)) [m].
  double pathAt(double u) const {
    const double f = (dir > 0 ? u : lap - u) / (lap / static_cast<double>(n));
    const auto k = std::min(n - 1, static_cast<std::size_t>(std::max(0.0, f)));
    return wrap(q[k] + (f - static_cast<double>(k)) * (q[k + 1] - q[k]));
  }
};

LanePath lanePath(const Road& r, const MovingCar& c) {
  LanePath p;
  p.dir = c.speed_mps < 0 ? -1 : 1;
  p.lap = lapLength(r);
  p.n = c.lap_v.size();
  const double margin = lapMargin(r, roadLength(r));
  std::vector<double> sigma(p.n + 1, 0.0);  // path length along the centreline direction
  double x0 = 0, y0 = 0, hd = 0;
  carAt(r, c, margin, x0, y0, hd);
  for (std::size_t j = 1; j <= p.n; ++j) {
    double x = 0, y = 0;
    carAt(r, c, margin + p.lap * static_cast<double>(j) / static_cast<double>(p.n), x, y, hd);
    sigma[j] = sigma[j - 1] + std::hypot(x - x0, y - y0);
    x0 = x;
    y0 = y;
  }
  p.q.resize(p.n + 1);
  for (std::size_t i = 0; i <= p.n; ++i)
    p.q[i] = p.dir > 0 ? sigma[i] : sigma[p.n] - sigma[p.n - i];
  return p;
}

/// One car of a lane during the integration: path position (unwrapped) and speed [m, m/s].
struct Driver {
  MovingCar* car = nullptr;
  double x = 0, v = 0;
  std::vector<double> vp;  ///< planned speed at each travel sample [m/s]
};

/// Planned speed of \p d at path length \p x: the ceiling that keeps v^2 |k| within the limit
/// [m/s].
double plannedSpeed(const LanePath& p, const Driver& d, double x) {
  const double f = p.index(x);
  const auto k = static_cast<std::size_t>(f);
  return d.vp[k] + (f - static_cast<double>(k)) * (d.vp[(k + 1) % p.n] - d.vp[k]);
}

/// The IDM's desired gap with no approach rate, s0 + v T [m].
double desiredGap(const FollowParams& f, double v) { return f.min_gap_m + v * f.headway_s; }

/// Moves every car of \p lane (index order) that starts closer to a car placed before it than the
/// desired gap (either way) back, behind that car, to the desired gap.
void separateStarts(const LanePath& p, const FollowParams& f, std::vector<Driver>& lane,
                    const Road& r) {
  for (std::size_t j = 1; j < lane.size(); ++j) {
    Driver& d = lane[j];
    double moved = 0;
    for (bool clash = true; clash;) {
      clash = false;
      for (std::size_t i = 0; i < j && !clash; ++i) {
        const double half = 0.5 * (lane[i].car->length_m + d.car->length_m);
        const double ahead = p.wrap(lane[i].x - d.x) - half,
                     behind = p.wrap(d.x - lane[i].x) - half;
        if (ahead >= desiredGap(f, d.v) - 1e-6 && behind >= desiredGap(f, lane[i].v) - 1e-6)
          continue;
        const double x = p.wrap(lane[i].x - half - desiredGap(f, d.v));
        moved += p.wrap(d.x - x);
        d.x = x;
        d.v = plannedSpeed(p, d, x);
        clash = true;
      }
      if (moved > p.length())
        throw std::runtime_error("[world] moving_cars: the lane of road '" + r.name +
                                 "' cannot hold " + std::to_string(lane.size()) + " cars " +
                                 std::to_string(f.min_gap_m) + " m + headway apart");
    }
  }
}

/// IDM acceleration (Treiber et al. 2000, eq. 1-2; s* bounded below by s0 as in Treiber & Kesting,
/// Traffic Flow Dynamics, 2013, sec. 11.3.4) of a car at speed \p v, desired speed \p v0, bumper
/// gap \p s to a leader at \p v_lead; \p s = +inf: no leader [m/s^2].
double idmAcceleration(const FollowParams& f, double v, double v0, double s, double v_lead) {
  const double free = 1.0 - std::pow(v / v0, 4);  // delta = 4
  if (!std::isfinite(s)) return f.accel_mps2 * free;
  const double s_star =
      f.min_gap_m +
      std::max(0.0,
               v * f.headway_s + v * (v - v_lead) / (2 * std::sqrt(f.accel_mps2 * f.decel_mps2)));
  return f.accel_mps2 * (free - (s_star / s) * (s_star / s));
}

/// One step of every driver of \p lane (parallel update from the old states), ballistic: x += v dt
/// + a dt^2 / 2 unless the car stops within the step (Treiber & Kesting 2013, sec. 11.2.2); the
/// planned speed at the new position is a hard ceiling (the IDM's free term brakes for a corner too
/// late).
void stepLane(const LanePath& p, const FollowParams& f, std::vector<Driver>& lane) {
  const double dt = World::kFollowStep_s;
  std::vector<std::size_t> order(lane.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return p.wrap(lane[a].x) < p.wrap(lane[b].x); });
  std::vector<double> x(lane.size()), v(lane.size());
  for (std::size_t r = 0; r < order.size(); ++r) {
    const Driver& d = lane[order[r]];
    const Driver& lead = lane[order[(r + 1) % order.size()]];
    const double s = order.size() < 2
                         ? INFINITY
                         : p.wrap(lead.x - d.x) - 0.5 * (lead.car->length_m + d.car->length_m);
    const double a =
        s <= 1e-3 ? -INFINITY : idmAcceleration(f, d.v, plannedSpeed(p, d, d.x), s, lead.v);
    double vn = d.v + a * dt, dx = 0.5 * (d.v + vn) * dt;
    if (vn < 0) {
      dx = std::isfinite(a) ? -0.5 * d.v * d.v / a : 0.0;
      vn = 0;
    }
    x[order[r]] = d.x + dx;
    v[order[r]] = std::min(vn, plannedSpeed(p, d, d.x + dx));
  }
  for (std::size_t i = 0; i < lane.size(); ++i) {
    lane[i].x = x[i];
    lane[i].v = v[i];
  }
}

void followLane(const Road& r, const FollowParams& f, std::vector<MovingCar*> cars) {
  const LanePath p = lanePath(r, *cars.front());
  std::vector<Driver> lane;
  for (MovingCar* c : cars) {
    if (c->lap_v.size() != p.n)
      throw std::logic_error("followTraffic: lane cars with different lap samples");
    Driver d;
    d.car = c;
    d.vp.resize(p.n);
    for (std::size_t i = 0; i < p.n; ++i) d.vp[i] = c->lap_v[p.dir > 0 ? i : (p.n - i) % p.n];
    double u = std::fmod(c->s0_m, p.lap);
    if (u < 0) u += p.lap;
    d.x = p.pathAt(u);
    d.v = plannedSpeed(p, d, d.x);
    lane.push_back(std::move(d));
  }
  separateStarts(p, f, lane, r);
  const auto steps = static_cast<std::size_t>(std::ceil(f.span_s / World::kFollowStep_s)) + 1;
  std::vector<double> u0(lane.size());
  for (std::size_t i = 0; i < lane.size(); ++i) {
    MovingCar& c = *lane[i].car;
    u0[i] = p.travelU(lane[i].x);
    // the start in the lap coordinate carPose reads (moved cars included)
    const double u = std::fmod(u0[i], p.lap);
    c.s0_m = p.dir > 0 ? u : std::fmod(p.lap - u, p.lap);
    c.follow_u.assign(1, 0.0);
    c.follow_u.reserve(steps + 1);
  }
  for (std::size_t k = 0; k < steps; ++k) {
    stepLane(p, f, lane);
    for (std::size_t i = 0; i < lane.size(); ++i)
      lane[i].car->follow_u.push_back(p.travelU(lane[i].x) - u0[i]);
  }
}

}  // namespace

void World::followTraffic(const FollowParams& f) {
  for (MovingCar& c : cars) c.follow_u.clear();
  if (f.span_s <= 0) return;
  // lanes: same road, same travel direction, same offset (MovingCar::lateral_m is drawn from the
  // lane widths, so equal lanes give equal doubles); index order within a lane
  std::map<std::tuple<int, int, double>, std::vector<MovingCar*>> lanes;
  for (MovingCar& c : cars)
    if (c.lap_t.size() >= 2 && c.lap_v.size() + 1 == c.lap_t.size())
      lanes[{c.road, c.speed_mps < 0 ? -1 : 1, c.lateral_m}].push_back(&c);
  for (auto& [key, lane] : lanes)
    followLane(roads[static_cast<std::size_t>(std::get<0>(key))], f, lane);
}

}  // namespace roadslam::sim

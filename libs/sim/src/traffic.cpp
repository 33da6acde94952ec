// The moving cars' laps: where a car is at time t (constant speed, planned lap or followed drive) and
// the curve-limited lap plan. The car-following integration is in following.cpp.
#include <algorithm>
#include <cmath>

#include "traffic.h"

namespace roadslam::sim {

double lapMargin(const Road& r, double len) { return r.closed ? 0.0 : std::min(15.0, 0.25 * len); }

double lapLength(const Road& r) {
  const double len = roadLength(r);
  return len - 2 * lapMargin(r, len);
}

void carAt(const Road& r, const MovingCar& car, double s, double& x, double& y, double& hd) {
  Vec2 p;
  double h;
  pointAtArcLength(r, s, p, h);
  hd = car.speed_mps < 0 ? h + M_PI : h;
  x = p.x + car.lateral_m * std::sin(hd);  // to the right of the travel direction
  y = p.y - car.lateral_m * std::cos(hd);
}

namespace {

/// The lap coordinate of \p car at \p t_s on its planned lap (lap_t at lap / (n - 1) spacing), t = 0
/// at the coordinate \p u0: the time table inverted, linear within a step.
double plannedLapCoordinate(const MovingCar& car, double lap, double u0, double t_s) {
  const auto& T = car.lap_t;
  const double step = lap / static_cast<double>(T.size() - 1), period = T.back();
  const double f = u0 / step;
  const std::size_t i = std::min(T.size() - 2, static_cast<std::size_t>(f));
  const double t0 = T[i] + (f - static_cast<double>(i)) * (T[i + 1] - T[i]);
  double tau = std::fmod(car.speed_mps < 0 ? t0 - t_s : t0 + t_s, period);
  if (tau < 0) tau += period;
  const std::size_t k = std::min<std::size_t>(T.size() - 2, std::upper_bound(T.begin(), T.end(), tau) - T.begin() - 1);
  const double dt = T[k + 1] - T[k];
  return step * (static_cast<double>(k) + (dt > 0 ? (tau - T[k]) / dt : 0.0));
}

/// How far \p car's lap coordinate has run since t = 0 on its followed drive (follow_u every
/// World::kFollowStep_s), linear within a step; outside the integrated span it keeps its first or last
/// step's speed (World::followTraffic integrates the drive's duration plus a margin).
double followedDistance(const MovingCar& car, double t_s) {
  const auto& D = car.follow_u;
  const double f = t_s / World::kFollowStep_s;
  const std::size_t last = D.size() - 1;
  const std::size_t k = f <= 0 ? 0 : std::min(last - 1, static_cast<std::size_t>(f));
  return D[k] + (f - static_cast<double>(k)) * (D[k + 1] - D[k]);
}

}  // namespace

CarPose World::carPose(const MovingCar& car, double t_s) const {
  const Road& r = roads[static_cast<std::size_t>(car.road)];
  const double len = roadLength(r);
  const double margin = lapMargin(r, len), lap = len - 2 * margin;
  double u = std::fmod(car.s0_m, lap);
  if (u < 0) u += lap;
  if (car.follow_u.size() >= 2) {
    u = std::fmod(car.speed_mps < 0 ? u - followedDistance(car, t_s) : u + followedDistance(car, t_s), lap);
    if (u < 0) u += lap;
  } else if (car.lap_t.size() >= 2) {
    u = plannedLapCoordinate(car, lap, u, t_s);
  } else {
    u = std::fmod(car.s0_m + car.speed_mps * t_s, lap);
    if (u < 0) u += lap;
  }
  CarPose out;
  carAt(r, car, u + margin, out.x, out.y, out.yaw);
  out.z = ground.height(out.x, out.y);
  if (surface.any()) out.z += surfaceOffset(out.x, out.y);
  return out;
}

void World::planTraffic(double lateral_accel_mps2, double accel_mps2) {
  for (MovingCar& car : cars) {
    car.lap_t.clear();
    car.lap_v.clear();
    car.follow_u.clear();
    if (lateral_accel_mps2 <= 0 || car.speed_mps == 0) continue;
    const Road& r = roads[static_cast<std::size_t>(car.road)];
    const double len = roadLength(r), margin = lapMargin(r, len), lap = len - 2 * margin;
    const std::size_t n = std::max<std::size_t>(16, static_cast<std::size_t>(std::ceil(lap / 0.5)));
    // the car's own path (its lane's offset changes a corner's radius), sampled every lap / n
    std::vector<double> x(n + 1), y(n + 1), seg(n), theta(n);
    for (std::size_t j = 0; j <= n; ++j) {
      double hd;
      carAt(r, car, margin + lap * static_cast<double>(j) / static_cast<double>(n), x[j], y[j], hd);
    }
    for (std::size_t j = 0; j < n; ++j) {
      seg[j] = std::hypot(x[j + 1] - x[j], y[j + 1] - y[j]);
      theta[j] = std::atan2(y[j + 1] - y[j], x[j + 1] - x[j]);
    }
    // speed limit at each sample: v^2 |k| <= a_lat, k the heading change over the two adjacent steps
    // (the lap is periodic: a closed road's start joins its end; an open road's wrap is a jump, no corner)
    std::vector<double> v(n);
    const double cruise = std::abs(car.speed_mps);
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t i = (j + n - 1) % n;
      const double k = (j == 0 && !r.closed)
                           ? 0.0
                           : std::remainder(theta[j] - theta[i], 2 * M_PI) / std::max(1e-6, 0.5 * (seg[i] + seg[j]));
      v[j] = std::min(cruise, std::sqrt(lateral_accel_mps2 / std::max(1e-9, std::abs(k))));
    }
    // v^2 changes by at most 2 a ds per step, both ways round the periodic lap (two turns reach every sample)
    for (std::size_t it = 1; it < 2 * n; ++it) {
      const std::size_t j = it % n, i = (it - 1) % n;
      v[j] = std::min(v[j], std::sqrt(v[i] * v[i] + 2 * accel_mps2 * seg[i]));
    }
    for (std::size_t it = 2 * n; it-- > 1;) {
      const std::size_t j = (it - 1) % n, i = it % n;
      v[j] = std::min(v[j], std::sqrt(v[i] * v[i] + 2 * accel_mps2 * seg[j]));
    }
    car.lap_v = v;
    car.lap_t.assign(n + 1, 0.0);
    for (std::size_t j = 0; j < n; ++j) car.lap_t[j + 1] = car.lap_t[j] + 2 * seg[j] / std::max(1e-6, v[j] + v[(j + 1) % n]);
  }
}

}  // namespace roadslam::sim

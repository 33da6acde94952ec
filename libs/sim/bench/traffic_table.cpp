// Planned traffic with and without car-following (World::followTraffic), sampled as gt_objects.json
// is (World::carPose every 0.1 s over the drive): same-direction pairs within 4.5 m (centres within
// 4.5 m, headings within 0.5 rad), the closest same-lane bumper gap, the largest lateral acceleration
// (v * yaw rate over 1 s windows) and braking (0.5 s windows). Prints a markdown table.
// Run: build/bench/sim_traffic_table [INI:DURATION_S ...] (default: the shipped urban loops)
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "roadslam/sim/simulator.h"

using namespace roadslam::sim;

namespace {

struct Figures {
  long pairs_within_4_5m = 0;
  double min_lane_gap_m = INFINITY, max_lateral_mps2 = 0, max_braking_mps2 = 0;
};

bool sameLane(const MovingCar& a, const MovingCar& b) {
  return a.road == b.road && (a.speed_mps < 0) == (b.speed_mps < 0) && a.lateral_m == b.lateral_m;
}

void pairFigures(const World& w, double duration_s, Figures& f) {
  std::vector<std::vector<CarPose>> P(w.cars.size());
  for (std::size_t i = 0; i < w.cars.size(); ++i)
    for (double t = 0; t <= duration_s + 1e-9; t += 0.1) P[i].push_back(w.carPose(w.cars[i], t));
  for (std::size_t a = 0; a < P.size(); ++a)
    for (std::size_t b = a + 1; b < P.size(); ++b)
      for (std::size_t k = 0; k < P[a].size(); ++k) {
        const double d = std::hypot(P[a][k].x - P[b][k].x, P[a][k].y - P[b][k].y);
        const double dyaw = std::remainder(P[a][k].yaw - P[b][k].yaw, 2 * M_PI);
        f.pairs_within_4_5m += d < 4.5 && std::abs(dyaw) < 0.5;
        if (sameLane(w.cars[a], w.cars[b]))
          f.min_lane_gap_m =
              std::min(f.min_lane_gap_m, d - 0.5 * (w.cars[a].length_m + w.cars[b].length_m));
      }
}

void motionFigures(const World& w, double duration_s, Figures& f) {
  const double dt = 0.5;
  for (const MovingCar& c : w.cars)
    for (double t = dt; t < duration_s - dt; t += 0.05) {
      const CarPose a = w.carPose(c, t - dt), b = w.carPose(c, t), d = w.carPose(c, t + dt);
      if (std::hypot(d.x - b.x, d.y - b.y) > 20) continue;  // an open road's wrap
      const double v = std::hypot(d.x - a.x, d.y - a.y) / (2 * dt);
      f.max_lateral_mps2 = std::max(
          f.max_lateral_mps2, std::abs(v * std::remainder(d.yaw - a.yaw, 2 * M_PI) / (2 * dt)));
      const double v1 = std::hypot(b.x - a.x, b.y - a.y) / dt,
                   v2 = std::hypot(d.x - b.x, d.y - b.y) / dt;
      f.max_braking_mps2 = std::max(f.max_braking_mps2, (v1 - v2) / dt);
    }
}

Figures figures(const World& w, double duration_s) {
  Figures f;
  pairFigures(w, duration_s, f);
  motionFigures(w, duration_s, f);
  return f;
}

void row(const ScenarioParams& p, const char* traffic, const Figures& f) {
  std::printf("| %s seed %llu, %.0f s | %s | %ld | %.2f | %.2f | %.2f |\n", p.name.c_str(),
              static_cast<unsigned long long>(p.seed), p.duration_s, traffic, f.pairs_within_4_5m,
              f.min_lane_gap_m, f.max_lateral_mps2, f.max_braking_mps2);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> runs(argv + 1, argv + argc);
  if (runs.empty()) {
    const std::string d = std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/";
    runs = {d + "urban-loop.ini:90", d + "urban-loop.ini:120", d + "urban-loop-hard.ini:90"};
  }
  std::printf(
      "| drive | traffic (2.5 m/s^2 planned) | same-direction pairs < 4.5 m | closest same-lane "
      "gap [m] | max lateral [m/s^2] | max braking [m/s^2] |\n|---|---|---|---|---|---|\n");
  for (const std::string& r : runs) {
    const auto colon = r.rfind(':');
    ScenarioParams p = ScenarioParams::fromFile(r.substr(0, colon));
    p.duration_s = colon == std::string::npos ? 90.0 : std::stod(r.substr(colon + 1));
    p.world.moving_car_lateral_accel_mps2 = 2.5;
    Road route;
    const World planned = buildWorld(p.world, p.seed, route);  // planned laps, not followed
    const Simulator followed(p);
    row(p, "planned", figures(planned, p.duration_s));
    row(p, "planned + following", figures(followed.world(), p.duration_s));
  }
  return 0;
}

#pragma once
// Simulated recordings for the jobs tests, generated once per build tree into the cache every test
// binary shares (sim::simulateCached: <build>/sim-cache/<scenario>-<duration>-<hash>, a completion
// marker written last makes an interrupted run regenerate, a lock file makes parallel tests take turns).
#include <filesystem>
#include <string>

#include "roadslam/sim/outputs.h"

namespace roadslam::jobs::test {

/// Urban loop shrunk to a 110 m x 70 m block (~330 m, ~40 s): small enough for the default suite.
inline sim::ScenarioParams smallLoop() {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/urban-loop.ini");
  p.world.length_m = 110;
  p.world.width_m = 70;
  p.world.moving_cars = 2;
  return p;
}

/// Simulates \p p into the build tree's drive cache unless done before; returns the folder.
inline std::string simulateOnce(const sim::ScenarioParams& p) { return sim::simulateCached(p, ROADSLAM_SIM_CACHE); }

}  // namespace roadslam::jobs::test

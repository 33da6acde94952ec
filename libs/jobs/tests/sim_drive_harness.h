#pragma once
// Harness of the simulated-drive tests: drives simulated once per build tree (sim::simulateCached, the
// cache every test binary shares), the roadslam-bounds job over them with GT poses, the eval's scores,
// and the check that no boundary vertex lies on a moving car (GT tracks).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "roadslam/jobs/bounds_job.h"
#include "roadslam/eval/boundary_metrics.h"
#include "roadslam/sim/outputs.h"

namespace roadslam::jobs::bounds_test {

namespace fs = std::filesystem;

/// Simulates \p duration_s of \p ini (with \p tweak applied) into the build tree's drive cache once.
inline std::string cachedDrive(const std::string& ini, double duration_s, void (*tweak)(sim::ScenarioParams&)) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/" + ini);
  p.duration_s = duration_s;
  if (tweak) tweak(p);
  return sim::simulateCached(p, ROADSLAM_SIM_CACHE);
}

struct Run {
  std::string out_dir;  ///< the job's output folder (boundaries.jsonl, frames/, summary.json)
  nlohmann::json summary;
  eval::BoundaryMetrics m;
};

/// How runBounds runs the job: live or whole-drive mode, GT poses or the odometry's.
struct Mode {
  bool whole_drive = false;
  bool gt_poses = true;
};

inline Run runBounds(const std::string& drive, const std::string& ini, const std::string& tag, Mode mode = {}) {
  jobs::BoundsRequest req;
  req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/" + ini;
  req.input_path = drive + "/velodyne.pcap";
  if (mode.gt_poses) req.trajectory_path = drive + "/gt_trajectory.tum";
  req.whole_drive = mode.whole_drive;
  req.out_dir = std::string(ROADSLAM_BINARY_DIR) + "/test_data/boundary_out_" + tag;
  req.png_every = 25;
  req.progress = false;
  Run r;
  r.out_dir = req.out_dir;
  r.summary = jobs::runBoundsJob(req);
  r.m = eval::evaluateBoundaryFiles(drive + "/gt_boundaries.json", drive + "/gt_trajectory.tum",
                                    req.out_dir + "/boundaries.jsonl");
  std::cout << tag << ": " << eval::toJson(r.m).dump() << "\n";
  return r;
}

/// The run \p r scored with stations along the GT path ahead (corners read across the road).
inline eval::BoundaryMetrics alongPath(const std::string& drive, const Run& r) {
  eval::BoundaryEvalParams path;
  path.stations = "path";
  const auto m = eval::evaluateBoundaryFiles(drive + "/gt_boundaries.json", drive + "/gt_trajectory.tum",
                                             r.out_dir + "/boundaries.jsonl", path);
  std::cout << r.out_dir << ", path stations: " << eval::toJson(m).dump() << "\n";
  return m;
}

/// Boundary vertices reported inside a moving car's footprint (+0.3 m), and the frames in which a
/// moving car was within 30 m of the vehicle (so the check had something to reject).
inline std::pair<int, int> verticesOnMovingCars(const std::string& drive, const std::string& out_dir) {
  std::ifstream fo(drive + "/gt_objects.json");
  const auto objects = nlohmann::json::parse(fo);
  std::ifstream fj(out_dir + "/boundaries.jsonl");
  std::string line;
  int on_cars = 0, near_frames = 0;
  while (std::getline(fj, line)) {
    const auto f = nlohmann::json::parse(line);
    if (!f.contains("left")) continue;
    const double t = f["stamp_s"].get<double>();
    const double vx = f["T_map_lidar"][3].get<double>(), vy = f["T_map_lidar"][7].get<double>();
    bool near = false;
    for (const auto& car : objects["moving_cars"]) {
      const auto& tr = car["track"];
      size_t k = 1;
      while (k + 1 < tr.size() && tr[k][0].get<double>() < t) ++k;
      const double t0 = tr[k - 1][0].get<double>(), t1 = tr[k][0].get<double>();
      const double u = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
      const double cx = (1 - u) * tr[k - 1][1].get<double>() + u * tr[k][1].get<double>();
      const double cy = (1 - u) * tr[k - 1][2].get<double>() + u * tr[k][2].get<double>();
      const double yaw = tr[k][4].get<double>();
      const double hl = 0.5 * car["length_m"].get<double>() + 0.3, hw = 0.5 * car["width_m"].get<double>() + 0.3;
      near = near || std::hypot(cx - vx, cy - vy) < 30.0;
      for (const char* side : {"left", "right"}) {
        if (!f[side]["found"].get<bool>()) continue;
        for (const auto& q : f[side]["polyline_map"]) {
          const double dx = q[0].get<double>() - cx, dy = q[1].get<double>() - cy;
          const double a = std::cos(yaw) * dx + std::sin(yaw) * dy, b = -std::sin(yaw) * dx + std::cos(yaw) * dy;
          on_cars += std::abs(a) <= hl && std::abs(b) <= hw;
        }
      }
    }
    near_frames += near;
  }
  return {on_cars, near_frames};
}


}  // namespace roadslam::jobs::bounds_test

// roadslam-eval: scores an estimated trajectory against ground truth (ATE, RPE, KITTI errors), or,
// with the `bounds` subcommand, estimated road boundaries against ground-truth curbs; `objects`: tracks
// against the simulator's moving cars (CLEAR MOT).
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "roadslam/common/cli.h"
#include "roadslam/eval/boundary_metrics.h"
#include "roadslam/eval/evaluate.h"
#include "roadslam/eval/mot_metrics.h"

int main(int argc, char** argv) {
  CLI::App app{"Trajectory evaluation: ATE (SE(3)-aligned and first-pose-aligned), RPE, KITTI "
               "relative translation/rotation errors over distance segments; `bounds`: road boundaries"};
  roadslam::eval::EvalRequest req;
  bool json = false;
  roadslam::addVersionFlag(app, "roadslam-eval");
  app.add_option("--gt", req.gt_path, "ground truth, TUM or KITTI 3x4")->check(CLI::ExistingFile);
  app.add_option("--est", req.est_path, "estimate, TUM or KITTI 3x4")->check(CLI::ExistingFile);
  app.add_option("--gt-times", req.gt_times_path, "times file for a KITTI-format GT")->check(CLI::ExistingFile);
  app.add_option("--est-times", req.est_times_path, "times file for a KITTI-format estimate")->check(CLI::ExistingFile);
  app.add_option("--calib", req.gt_calib_path, "KITTI odometry calib.txt: its Tr turns camera-frame GT poses into LiDAR ones")
      ->check(CLI::ExistingFile);
  app.add_option("--max-dt", req.max_dt_s, "association tolerance [s]");
  app.add_option("--segments", req.metrics.segment_lengths_m, "segment lengths [m] (default: KITTI's or 10-90 % of the path)");
  app.add_option("--plot", req.plot_path, "write a PNG: trajectories from above and error along the distance");
  app.add_flag("--json", json, "print JSON instead of text");

  auto* bounds = app.add_subcommand("bounds", "road boundaries vs ground-truth curbs in a band ahead");
  std::string b_gt, b_traj, b_est;
  roadslam::eval::BoundaryEvalParams bp;
  bounds->add_option("--gt", b_gt, "gt_boundaries.json (simulator)")->required()->check(CLI::ExistingFile);
  bounds->add_option("--gt-trajectory", b_traj, "ground-truth poses T_world_lidar, TUM")->required()->check(CLI::ExistingFile);
  bounds->add_option("--est", b_est, "boundaries.jsonl (roadslam-bounds)")->required()->check(CLI::ExistingFile);
  bounds->add_option("--band-min", bp.band_min_x_m, "band ahead, start [m]");
  bounds->add_option("--band-max", bp.band_max_x_m, "band ahead, end [m]");
  bounds->add_option("--stations", bp.stations, "axis: on the vehicle's x axis (default); path: along the GT path ahead")
      ->check(CLI::IsMember({"path", "axis"}));
  bounds->add_flag("--est-in-gt-frame", bp.est_in_gt_frame,
                   "read the estimate with the GT pose, not its own T_map_lidar (its map frame is the GT world)");
  bounds->add_flag("--json", json, "print JSON instead of text");
  std::string b_csv;
  bounds->add_option("--frames-csv", b_csv, "also write each frame's score (found, stations, errors per side) as CSV");
  auto* objects = app.add_subcommand("objects", "tracks (roadslam-map [objects]) vs the simulator's moving cars: CLEAR MOT");
  std::string o_gt, o_traj, o_run;
  roadslam::eval::MotParams mp;
  objects->add_option("--gt", o_gt, "gt_objects.json (simulator)")->required()->check(CLI::ExistingFile);
  objects->add_option("--gt-trajectory", o_traj, "ground-truth poses T_world_lidar, TUM")->required()->check(CLI::ExistingFile);
  objects->add_option("--run", o_run, "roadslam-map output folder (tracks.csv, trajectory_odometry.tum)")->required()
      ->check(CLI::ExistingDirectory);
  objects->add_option("--range", mp.max_range_m, "GT cars within this range of the lidar [m]");
  objects->add_option("--match-distance", mp.match_distance_m, "largest centre distance of a match [m]");
  objects->add_option("--speed-after", mp.speed_after_s, "speed error counted for tracks this old [s]");
  objects->add_option("--min-returns", mp.min_returns,
                      "GT cars with fewer lidar points in the turn (gt_objects.json returns) are don't care");
  objects->add_option("--switch-gap", mp.switch_gap_s,
                      "id switches of a car unmatched for longer are also counted apart (after a gap) [s]");
  std::string o_events;
  objects->add_option("--events", o_events, "also write every miss, false positive and id switch as CSV");
  objects->add_flag("--json", json, "print JSON instead of text");
  bool o_ghosts = false;
  objects->add_flag("--ghosts", o_ghosts,
                    "also count the map's points (RUN/map.ply) and OctoMap leaves (RUN/map.bt) on the moving cars' swept paths");
  double o_ghost_range = 0;
  objects->add_option("--ghost-range", o_ghost_range,
                      "with --ghosts: also count the ghosts of the paths swept within this range of the lidar [m]");
  bool o_ghost_unseen = false;
  objects->add_flag("--ghosts-unseen", o_ghost_unseen,
                    "with --ghosts: the paths also sweep the GT samples where the car had no lidar return (so road points under hidden cars' boxes count too)");
  CLI11_PARSE(app, argc, argv);
  try {
    if (*objects) {
      mp.keep_events = !o_events.empty();
      const auto m = roadslam::eval::evaluateMotFiles(o_gt, o_traj, o_run, mp);
      if (!o_events.empty()) {
        std::ofstream out(o_events);
        if (!(out << roadslam::eval::eventsCsv(m))) throw std::runtime_error("cannot write '" + o_events + "'");
      }
      auto j = roadslam::eval::toJson(m);
      std::string text = roadslam::eval::toText(m);
      if (o_ghosts) {
        const auto g = roadslam::eval::countGhostPoints(o_gt, o_traj, o_run + "/trajectory.tum", o_run + "/map.ply", 0.3, 0,
                                                        !o_ghost_unseen);
        j["map_points"] = g.map_points, j["ghost_points"] = g.ghost_points;
        text += "ghost points        " + std::to_string(g.ghost_points) + " of " + std::to_string(g.map_points) + " map points\n";
        if (std::ifstream(o_run + "/map.bt")) {
          const auto v = roadslam::eval::countGhostVoxels(o_gt, o_traj, o_run + "/trajectory.tum", o_run + "/map.bt", 0.3, 0,
                                                          !o_ghost_unseen);
          j["octomap_occupied_leaves"] = v.map_points, j["octomap_ghost_leaves"] = v.ghost_points;
          text += "ghost voxels        " + std::to_string(v.ghost_points) + " of " + std::to_string(v.map_points) +
                  " occupied OctoMap leaves (map.bt)\n";
        }
      }
      if (o_ghosts && o_ghost_range > 0) {
        const std::string tr = o_run + "/trajectory.tum";
        const auto g = roadslam::eval::countGhostPoints(o_gt, o_traj, tr, o_run + "/map.ply", 0.3, o_ghost_range, !o_ghost_unseen);
        j["ghost_points_within_range"] = g.ghost_points;
        text += "ghost points        " + std::to_string(g.ghost_points) + " on paths swept within the ghost range\n";
        if (std::ifstream(o_run + "/map.bt")) {
          const auto v = roadslam::eval::countGhostVoxels(o_gt, o_traj, tr, o_run + "/map.bt", 0.3, o_ghost_range, !o_ghost_unseen);
          j["octomap_ghost_leaves_within_range"] = v.ghost_points;
          text += "ghost voxels        " + std::to_string(v.ghost_points) + " on paths swept within the ghost range\n";
        }
      }
      std::cout << (json ? j.dump(2) + "\n" : text);
      return 0;
    }
    if (*bounds) {
      const auto m = roadslam::eval::evaluateBoundaryFiles(b_gt, b_traj, b_est, bp);
      std::cout << (json ? roadslam::eval::toJson(m).dump(2) + "\n" : roadslam::eval::toText(m));
      if (!b_csv.empty()) {
        std::ofstream out(b_csv);
        if (!(out << roadslam::eval::perFrameCsv(m))) throw std::runtime_error("cannot write '" + b_csv + "'");
      }
      return 0;
    }
    if (req.gt_path.empty() || req.est_path.empty()) {
      std::cerr << "roadslam-eval: --gt and --est are required (or use the bounds subcommand)\n";
      return 1;
    }
    const auto out = roadslam::eval::evaluate(req);
    for (const auto& w : out.warnings) std::cerr << "roadslam-eval: warning: " << w << "\n";
    if (json) {
      std::cout << roadslam::eval::toJson(out, req).dump(2) << "\n";
    } else {
      std::cout << roadslam::eval::toText(out.metrics);
    }
  } catch (const std::exception& e) {
    std::cerr << "roadslam-eval: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

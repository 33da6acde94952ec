// roadslam-view: replay a recording with the SLAM results over it, in a window or as PNG renders.
#include <CLI/CLI.hpp>
#include <iostream>

#include "roadslam/common/cli.h"
#include "roadslam/viewer/app.h"

int main(int argc, char** argv) {
  CLI::App app{"Replay viewer: a recording (MRPT .rawlog) with roadslam-map / roadslam-bounds results over it"};
  roadslam::viewer::ViewRequest req;
  std::string color = "height", camera = "follow";
  roadslam::addVersionFlag(app, "roadslam-view");
  auto* rec = app.add_option("recording,--input", req.inputs.recording,
                              "MRPT rawlog (observations or sensory-frames format), Velodyne pcap or KITTI .bin folder")
                  ->check(CLI::ExistingPath);
  auto* udp = app.add_option("--udp", req.live.udp_port, "live: show the sweeps of a VLP-16 sending to this UDP data port (2368)")
                  ->check(CLI::Range(0, 65535));
  auto* grab = app.add_option("--grab", req.live.grab_ini, "live: every LiDAR and the CAN bus of this roadslam-grab ini")
                   ->check(CLI::ExistingFile);
  app.add_option("--record", req.live.record_dir, "live: also record the session into DIR, as roadslam-grab does");
  app.add_option("--sweeps", req.live_sweeps, "live --render: render once this many sweeps arrived")->check(CLI::PositiveNumber);
  app.add_option("--timeout", req.live_timeout_s, "live --render: give up after this many seconds")->check(CLI::PositiveNumber);
  app.add_option("--keep", req.live_keep_s, "live: seconds of sweeps kept to step back through")->check(CLI::PositiveNumber);
  app.add_option("--map", req.inputs.map_dir, "roadslam-map output folder")->check(CLI::ExistingDirectory);
  app.add_option("--bounds", req.inputs.bounds_dir, "roadslam-bounds output folder")->check(CLI::ExistingDirectory);
  app.add_option("--gt", req.inputs.ground_truth, "ground-truth trajectory (TUM)")->check(CLI::ExistingFile);
  app.add_flag("--grid", req.inputs.grid, "draw the map folder's occupancy grid (grid.gridmap) on the ground under the car");
  app.add_flag("--octomap", req.inputs.octomap, "draw the map folder's OctoMap (map.bt) occupied voxels instead of its point map");
  app.add_option("--can", req.inputs.can_log, "candump log of the same drive: speed and yaw rate plotted under the view")
      ->check(CLI::ExistingFile);
  app.add_option("--vehicle", req.inputs.vehicle_ini, "the car's vehicle ini (ini/vehicles/...), with --can")->check(CLI::ExistingFile);
  app.add_option("--render", req.render_png, "render the scene at --at into this PNG (no window) and exit");
  app.add_option("--at", req.at_s, "time for --render, seconds from the start of the recording (0 to its length)");
  app.add_option("--render-sequence", req.sequence_dir, "render every --every-th sweep into DIR/NNNNNN.png and exit");
  app.add_option("--every", req.every, "with --render-sequence: one PNG per N sweeps")->check(CLI::PositiveNumber);
  app.add_option("--video", req.video, "encode the --every-th sweeps into this MP4 through ffmpeg and exit");
  app.add_option("--fps", req.fps, "with --video: frames per second")->check(CLI::PositiveNumber);
  app.add_option("--size", req.size, "picture / window size WxH in pixels (e.g. 1280x720)");
  app.add_option("--color", color, "sweep colour: height, intensity, ring, time");
  app.add_option("--camera", camera, "camera: follow, top, orbit");
  app.add_option("--script", req.script, "window: run these commands (key X, wait S, screenshot PATH, quit)")
      ->check(CLI::ExistingFile);
  app.add_option("--run-slam", req.run_slam_ini, "run the odometry of this config (e.g. ini/default.ini) while replaying")
      ->check(CLI::ExistingFile);
  app.add_flag("--no-index-cache", req.no_index_cache,
               "keep nothing in the cache folder ($XDG_CACHE_HOME/roadslam): index the rawlog again, convert a pcap "
               "or KITTI folder into a temporary folder removed at exit");
  CLI11_PARSE(app, argc, argv);
  if (int(rec->count() > 0) + int(udp->count() > 0) + int(grab->count() > 0) != 1) {
    std::cerr << "roadslam-view: give one of a recording, --udp PORT or --grab INI\n" << app.help();
    return 2;
  }
  if (!req.live.record_dir.empty() && !req.isLive()) {
    std::cerr << "roadslam-view: --record belongs to a live view (--udp or --grab)\n";
    return 2;
  }
  try {
    req.color_by = roadslam::viewer::parseColorBy(color);
    req.camera = roadslam::viewer::parseCameraMode(camera);
    return roadslam::viewer::runView(req, std::cout, std::cerr);
  } catch (const std::exception& e) {
    std::cerr << "roadslam-view: " << e.what() << "\n";
    return 1;
  }
}

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
  app.add_option("recording", req.inputs.recording, "MRPT rawlog (observations or sensory-frames format), Velodyne pcap or KITTI .bin folder")
      ->required()->check(CLI::ExistingPath);
  app.add_option("--map", req.inputs.map_dir, "roadslam-map output folder")->check(CLI::ExistingDirectory);
  app.add_option("--bounds", req.inputs.bounds_dir, "roadslam-bounds output folder")->check(CLI::ExistingDirectory);
  app.add_option("--gt", req.inputs.ground_truth, "ground-truth trajectory (TUM)")->check(CLI::ExistingFile);
  app.add_flag("--octomap", req.inputs.octomap, "draw the map folder's OctoMap (map.bt) occupied voxels instead of its point map");
  app.add_option("--can", req.inputs.can_log, "candump log of the same drive: speed and yaw rate plotted under the view")
      ->check(CLI::ExistingFile);
  app.add_option("--vehicle", req.inputs.vehicle_ini, "the car's vehicle ini (ini/vehicles/...), with --can")->check(CLI::ExistingFile);
  app.add_option("--render", req.render_png, "render the scene at --at into this PNG (no window) and exit");
  app.add_option("--at", req.at_s, "time for --render, seconds from the start of the recording");
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
  app.add_flag("--no-index-cache", req.no_index_cache, "rebuild the rawlog index and do not write REC.idx");
  CLI11_PARSE(app, argc, argv);
  try {
    req.color_by = roadslam::viewer::parseColorBy(color);
    req.camera = roadslam::viewer::parseCameraMode(camera);
    return roadslam::viewer::runView(req, std::cout, std::cerr);
  } catch (const std::exception& e) {
    std::cerr << "roadslam-view: " << e.what() << "\n";
    return 1;
  }
}

// roadslam-eval: scores an estimated trajectory against ground truth (ATE, RPE, KITTI errors).
#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>

#include "roadslam/eval/evaluate.h"

int main(int argc, char** argv) {
  CLI::App app{"Trajectory evaluation: ATE (SE(3)-aligned and first-pose-aligned), RPE, KITTI "
               "relative translation/rotation errors over distance segments"};
  roadslam::eval::EvalRequest req;
  bool json = false;
  app.add_option("--gt", req.gt_path, "ground truth, TUM or KITTI 3x4")->required()->check(CLI::ExistingFile);
  app.add_option("--est", req.est_path, "estimate, TUM or KITTI 3x4")->required()->check(CLI::ExistingFile);
  app.add_option("--gt-times", req.gt_times_path, "times file for a KITTI-format GT")->check(CLI::ExistingFile);
  app.add_option("--est-times", req.est_times_path, "times file for a KITTI-format estimate")->check(CLI::ExistingFile);
  app.add_option("--max-dt", req.max_dt_s, "association tolerance [s]");
  app.add_option("--segments", req.metrics.segment_lengths_m, "segment lengths [m] (default: KITTI's or 10-90 % of the path)");
  app.add_option("--plot", req.plot_path, "write a PNG: trajectories from above and error along the distance");
  app.add_flag("--json", json, "print JSON instead of text");
  CLI11_PARSE(app, argc, argv);
  try {
    const auto out = roadslam::eval::evaluate(req);
    if (json) {
      std::cout << roadslam::eval::toJson(out.metrics).dump(2) << "\n";
    } else {
      std::cout << roadslam::eval::toText(out.metrics);
    }
  } catch (const std::exception& e) {
    std::cerr << "roadslam-eval: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

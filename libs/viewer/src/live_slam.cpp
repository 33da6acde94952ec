#include "roadslam/viewer/live_slam.h"

#include <chrono>

#include "roadslam/common/config.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/velodyne/decoder_params.h"

namespace roadslam::viewer {

struct LiveSlam::Impl {
  std::unique_ptr<pipeline::Pipeline> pipe;
};

LiveSlam::LiveSlam(const std::string& config_ini, const std::string& recording, ViewerModel& model)
    : model_(model), impl_(std::make_unique<Impl>()) {
  const auto cfg = loadIniFile(config_ini);
  odometry::Params op;
  op.loadFromConfigFile(*cfg);
  velodyne::DecoderParams dp;  // read by the source; loaded here so that its keys are checked too
  dp.loadFromConfigFile(*cfg, "velodyne");
  datasets::KittiParams kp;
  kp.loadFromConfigFile(*cfg, "kitti");
  auto source = pipeline::openNonEmptySource(recording, *cfg);
  cfg->checkEntries(false);
  pipeline::Stages stages;
  stages.poses = std::make_unique<pipeline::OdometryPoses>(op, false);
  impl_->pipe = std::make_unique<pipeline::Pipeline>(std::move(source), std::move(stages));
  thread_ = std::thread([this] { run(*impl_); });
}

LiveSlam::~LiveSlam() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void LiveSlam::run(Impl& impl) {
  try {
    while (!stop_) {
      const auto f = impl.pipe->next();
      if (!f) break;
      const auto& r = *f->pose.odometry;
      FrameResult out;
      out.stamp_s = r.stamp_s;
      out.T_map_lidar = r.T_world_lidar;
      out.status = odometry::toString(r.status);
      out.keyframe = r.keyframe;
      out.ms = r.ms_total;
      out.inliers = r.inliers;
      if (r.status != odometry::FrameStatus::Skipped) model_.postFrame(out);
      last_stamp_s_ = r.stamp_s;
      ++frames_;
    }
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(error_mutex_);
    error_ = e.what();
  }
  done_ = true;
}

void LiveSlam::waitUntil(double t_s) {
  while (!done_ && last_stamp_s_ < t_s) std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

std::string LiveSlam::error() const {
  std::lock_guard<std::mutex> lock(error_mutex_);
  return error_;
}

}  // namespace roadslam::viewer

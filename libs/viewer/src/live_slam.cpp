#include "roadslam/viewer/live_slam.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <mrpt/obs/CObservationGPS.h>

#include "roadslam/common/config.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/objects/stage.h"
#include "roadslam/pipeline/live_gnss.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/pipeline/stage_factory.h"
#include "roadslam/sources/observation_packet_source.h"
#include "roadslam/sources/sweep_source.h"
#include "roadslam/velodyne/decoder_params.h"

namespace roadslam::viewer {

struct LiveSlam::Impl {
  std::unique_ptr<pipeline::Pipeline> pipe;
  sources::ObservationPacketSource* live = nullptr;  // owned by the pipeline's source
  std::shared_ptr<pipeline::LiveGnss> gnss;          // live: the online GNSS correction, a stage of the pipeline
};

namespace {
// The config, with the keys of every component the odometry's source and stage read checked.
struct Config {
  std::unique_ptr<CheckedConfig> cfg;
  pipeline::ChainParams chain;
  velodyne::DecoderParams decoder;
  gnss_fusion::GnssFusionParams gnss;
  explicit Config(const std::string& path) : cfg(loadIniFile(path)) {
    chain.odometry.loadFromConfigFile(*cfg);
    chain.objects.loadFromConfigFile(*cfg, "objects", "preprocess");
    chain.tracking.loadFromConfigFile(*cfg, "tracking");
    gnss.loadFromConfigFile(*cfg, "gnss_fusion");
    sources::loadSourceSections(*cfg);  // a recording's source reads them: their keys are checked too
    decoder.loadFromConfigFile(*cfg, "velodyne");
  }
};

/// The odometry, with [objects] enabled the objects stage after it (as roadslam-map runs them), and
/// live the online GNSS correction.
pipeline::StageList stagesFor(const Config& c, std::shared_ptr<pipeline::LiveGnss> gnss = nullptr) {
  pipeline::StageRequest r;
  r.live_gnss = std::move(gnss);
  return pipeline::buildStages(c.chain, std::move(r));
}

/// The sweep's boxes as the map folder's tracks.csv and objects.csv hold them (map frame).
ObjectBoxes boxesOf(const pipeline::PipelineFrame& f) {
  ObjectBoxes out;
  out.stamp_s = f.pose.ok ? f.pose.t_ref : f.pose.stamp_s;
  for (const objects::Track& t : f.objects->tracks) {
    out.boxes.push_back({t.id, t.moving, t.box(), t.x(2), t.x(3)});
  }
  if (!f.pose.ok) return out;
  for (std::size_t k = 0; k < f.objects->objects.size(); ++k) {
    if (k < f.objects->object_track.size() && f.objects->object_track[k] >= 0) continue;  // drawn as its track
    // as objects.csv holds it (objects::objectsCsvRows)
    out.boxes.push_back({-1, false, f.objects->objects[k].box.placed(f.pose.ref), 0, 0});
  }
  return out;
}
}  // namespace

LiveSlam::LiveSlam(const std::string& config_ini, const std::string& recording, ViewerModel& model)
    : model_(model), impl_(std::make_unique<Impl>()) {
  Config c(config_ini);
  auto source = pipeline::openNonEmptySource(recording, *c.cfg);
  c.cfg->checkEntries(false);
  impl_->pipe = std::make_unique<pipeline::Pipeline>(std::move(source), stagesFor(c));
  thread_ = std::thread([this] { run(*impl_); });
}

LiveSlam::LiveSlam(const std::string& config_ini, const std::string& sensor_label, const std::string& name,
                   ViewerModel& model)
    : model_(model), impl_(std::make_unique<Impl>()) {
  Config c(config_ini);
  c.cfg->checkEntries(false);
  auto packets = std::make_unique<sources::ObservationPacketSource>(sensor_label, name);
  impl_->live = packets.get();
  impl_->gnss = std::make_shared<pipeline::LiveGnss>(c.gnss);
  auto sweeps = std::make_unique<sources::SweepSource>(std::move(packets), c.decoder);
  impl_->pipe = std::make_unique<pipeline::Pipeline>(std::move(sweeps), stagesFor(c, impl_->gnss));
  thread_ = std::thread([this] { run(*impl_); });
}

void LiveSlam::post(const std::shared_ptr<mrpt::obs::CObservation>& obs) {
  if (!impl_->live) return;
  if (const auto* g = dynamic_cast<const mrpt::obs::CObservationGPS*>(obs.get()))
    impl_->gnss->post(sources::gpsFixFromObservation(*g));
  else
    impl_->live->post(obs);
}

const pipeline::LiveGnss* LiveSlam::gnss() const { return impl_->gnss.get(); }

void LiveSlam::close() {
  if (impl_->live) impl_->live->close();
}

LiveSlam::~LiveSlam() {
  stop_ = true;
  close();
  if (thread_.joinable()) thread_.join();
}

void LiveSlam::run(Impl& impl) {
  try {
    while (!stop_) {
      const auto f = impl.pipe->next();
      if (!f && impl.pipe->source().finished()) break;
      if (!f) continue;  // live: no sweep ready yet
      const auto& r = *f->pose.odometry;
      ViewerFrame out;
      out.stamp_s = r.stamp_s;
      out.T_map_lidar = r.T_world_lidar;
      out.status = odometry::toString(r.status);
      out.keyframe = r.keyframe;
      out.ms = r.ms_total;
      out.inliers = r.inliers;
      out.T_enu_lidar = f->T_enu_lidar;
      if (r.status != odometry::FrameStatus::Skipped) model_.postFrame(out);
      if (f->objects) model_.postObjects(boxesOf(*f));
      last_stamp_s_ = r.stamp_s;
      ++frames_;
    }
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(error_mutex_);
    error_ = e.what();
  }
  done_ = true;
}

bool LiveSlam::waitUntil(double t_s, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(std::min(timeout_s, 1e7));
  while (!done_ && last_stamp_s_ < t_s) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

std::string LiveSlam::error() const {
  std::lock_guard<std::mutex> lock(error_mutex_);
  return error_;
}

}  // namespace roadslam::viewer

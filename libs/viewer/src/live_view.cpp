// roadslam-view --udp / --grab: the live view (live_feed.h) in the window, or one headless render.
#include <chrono>
#include <cstdio>
#include <thread>

#include "roadslam/viewer/app.h"
#include "roadslam/gnss/geo.h"
#include "roadslam/pipeline/live_gnss.h"
#include "roadslam/viewer/live_slam.h"
#include "roadslam/viewer/render.h"
#include "roadslam/viewer/replay.h"
#include "roadslam/viewer/window.h"

namespace roadslam::viewer {

namespace {

std::size_t sweepsIn(const rawlog::ObservationIndex& idx, std::size_t from, std::size_t count) {
  for (std::size_t i = from; i < idx.size(); ++i) count += holdsSweep(idx.className(i));
  return count;
}

/// Polls until \p wanted sweeps arrived or \p timeout_s passed; returns the sweeps seen.
std::size_t waitForSweeps(ViewerModel& model, std::size_t wanted, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  std::size_t sweeps = 0;
  while (sweeps < wanted && std::chrono::steady_clock::now() < until) {
    const std::size_t first = model.recording().size();
    model.poll();
    sweeps = sweepsIn(model.recording(), first, sweeps);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return sweeps;
}

}  // namespace

int runLiveView(const ViewRequest& req, std::ostream& out, std::ostream& err) {
  if (!req.sequence_dir.empty() || !req.video.empty())
    throw std::runtime_error("--render-sequence and --video need a recording; a live view renders one picture (--render)");
  if (!req.inputs.map_dir.empty() || !req.inputs.bounds_dir.empty() || !req.inputs.ground_truth.empty() ||
      !req.inputs.can_log.empty())
    throw std::runtime_error("--map, --bounds, --gt and --can belong to a recording, not to a live view");
  const auto [w, h] = parseSize(req.size);
  WindowOptions window{w, h, req.script, {}};
  const bool headless = !req.render_png.empty();
  if (!headless) checkWindowRequest(window);

  auto live = std::make_unique<sources::LiveObservations>("live view", req.live_keep_s);
  sources::LiveObservations& sink = *live;
  ViewerInputs in = req.inputs;
  in.recording = req.live.grab_ini.empty() ? "udp:" + std::to_string(req.live.udp_port) : req.live.grab_ini;
  ViewerModel model(in, std::move(live));
  std::unique_ptr<LiveSlam> slam;  // the odometry on the first LiDAR's sweeps, as they arrive
  if (!req.run_slam_ini.empty())
    slam = std::make_unique<LiveSlam>(req.run_slam_ini, LiveFeed::firstSensorLabel(req.live), in.recording, model);
  LiveSlam* odometry = slam.get();
  LiveFeed feed(req.live, sink, [odometry](const std::shared_ptr<mrpt::obs::CObservation>& o) {
    if (odometry) odometry->post(o);
  });  // declared after the model and the odometry: stopped before they go
  err << "roadslam-view: live from " << feed.name() << (slam ? ", odometry running" : "") << "\n";
  Replay replay(model);
  replay.options().color_by = req.color_by;
  replay.options().camera = req.camera;
  if (!headless) {
    window.status = [&feed, odometry] {
      const pipeline::LiveGnss* g = odometry ? odometry->gnss() : nullptr;
      return feed.statusLine() + (g && g->counts().epochs > 0 ? " | " + g->statusLine() : "");
    };
    const int code = runWindow(replay, window, out, err);
    feed.stop();
    out << feed.statusLine() << "\n";
    if (slam) out << "odometry (--run-slam): " << slam->frames() << " sweeps\n";
    return code;
  }
  const std::size_t sweeps = waitForSweeps(model, req.live_sweeps, req.live_timeout_s);
  // Rendered before the feed stops: stopping flushes the sweep in progress, a partial one.
  out << feed.statusLine() << "\n";
  if (sweeps == 0) {
    err << "roadslam-view: no sweep arrived from " << feed.name() << " within " << req.live_timeout_s
        << " s (is the sensor on, and sending to this host's address?)\n";
    return 1;
  }
  if (sweeps < req.live_sweeps)
    err << "roadslam-view: warning: " << sweeps << " of " << req.live_sweeps << " sweeps within " << req.live_timeout_s
        << " s\n";
  if (slam) {  // the odometry catches up with the newest sweep (it needs the next one to close it)
    slam->waitUntil(model.endTime() - 0.15, 5.0);
    model.takePosted();
    out << "odometry (--run-slam): " << slam->frames() << " sweeps, " << model.frames().size() << " frames posted";
    if (!model.frames().empty()) {
      const Eigen::Vector3d p = model.frames().back().T_map_lidar.translation();
      char at[120];
      std::snprintf(at, sizeof at, ", the last at %.3f %.3f %.3f m", p.x(), p.y(), p.z());
      out << at;
    }
    out << "\n";
    const pipeline::LiveGnss* g = slam->gnss();
    if (g && g->counts().epochs > 0) {
      out << g->statusLine();
      const ViewerFrame* last = nullptr;  // the newest corrected frame
      for (const auto& f : model.frames())
        if (f.T_enu_lidar) last = &f;
      if (last && g->origin()) {
        const Eigen::Vector3d p = last->T_enu_lidar->translation();
        const gnss::Geodetic geo = gnss::EnuFrame(*g->origin()).toGeodetic(p);
        char at[200];
        std::snprintf(at, sizeof at, "; the last corrected frame (t = %.3f s) at ENU %.3f %.3f %.3f m, lat %.8f lon %.8f h %.3f",
                      last->stamp_s, p.x(), p.y(), p.z(), geo.lat_deg, geo.lon_deg, geo.h_m);
        out << at;
      }
      out << "\n";
    }
    if (!slam->error().empty()) err << "roadslam-view: warning: the odometry stopped: " << slam->error() << "\n";
  }
  out << summaryLine(model) << "\n";
  replay.advance(0);  // to the live edge
  PngRenderer renderer(w, h);
  renderCurrent(replay, renderer, req.render_png);
  out << req.render_png << ": live, observation "
      << (replay.currentObservation() ? std::to_string(*replay.currentObservation()) : "-") << "\n";
  feed.stop();
  return 0;
}

}  // namespace roadslam::viewer

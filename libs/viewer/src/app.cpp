#include "roadslam/viewer/app.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/viewer/live_slam.h"
#include "roadslam/viewer/recording_open.h"
#include "roadslam/viewer/render.h"
#include "roadslam/viewer/replay.h"
#include "roadslam/viewer/window.h"

namespace roadslam::viewer {

std::pair<int, int> parseSize(const std::string& text) {
  int w = 0, h = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 64 || h < 64 || w > 8192 || h > 8192)
    throw std::invalid_argument("size '" + text + "': use WxH, 64-8192 pixels each (e.g. 1280x720)");
  return {w, h};
}

std::string summaryLine(ViewerModel& m) {
  const auto& idx = m.recording();
  const std::string lidar = m.lidarModel().text;
  std::string name = m.inputs().name(), how = m.live() ? " (live)" : "";
  if (m.session() && m.session()->segments() > 1) {
    char text[96];
    std::snprintf(text, sizeof text, " (%zu segments%s)", m.session()->segments(),
                  m.indexing() ? ", indexing in the background" : "");
    how = text;
  } else if (m.indexing()) {
    char text[64];
    std::snprintf(text, sizeof text, " so far (indexing in the background: %.0f %%)", 100 * m.indexProgress());
    how = text;
  } else if (const auto* r = m.rawlog()) {
    char text[64];
    std::snprintf(text, sizeof text, " (index %s, %.0f ms)", r->openInfo().from_cache ? "cached" : "built",
                  r->openInfo().seconds * 1e3);
    how = text;
  }
  char buf[700];
  std::snprintf(buf, sizeof buf,
                "%s: %zu observations over %.1f s%s%s; %zu frames, %zu loops, %zu map points, "
                "%zu boundary sweeps, %zu ground-truth poses, %zu CAN samples, %zu OctoMap voxels, %zu grid cells occupied",
                name.c_str(), idx.size(), m.endTime() - m.startTime(), how.c_str(),
                lidar.empty() ? "" : ("; lidar " + lidar).c_str(), m.frames().size(),
                m.loops().size(), m.mapPoints().size(), m.boundaries().size(), m.groundTruth().size(), m.can().size(), m.octoVoxels().size(),
                m.grid() ? m.grid()->occupied : std::size_t(0));
  return buf;
}

std::string atTimeProblem(double at_s, double duration_s, const std::string& name) {
  constexpr double kSlack_s = 0.1;  // a sweep at 10 Hz: the last one covers this long past its stamp
  char text[160];
  if (at_s < 0) {
    std::snprintf(text, sizeof text, "--at %g s is before the start of ", at_s);
    return text + name + " (--at counts seconds from its start)";
  }
  if (!(at_s <= duration_s + kSlack_s)) {
    std::snprintf(text, sizeof text, "--at %g s is past the end of ", at_s);
    std::string msg = text + name;
    std::snprintf(text, sizeof text, " (%.1f s long)", duration_s);
    return msg + text;
  }
  return {};
}

void encodeVideo(const std::string& png_dir, const std::string& mp4, double fps) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
    throw std::runtime_error("--video needs ffmpeg (Debian: apt install ffmpeg); --render-sequence DIR writes the "
                             "pictures without it");
  }
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  const std::string cmd = "ffmpeg -y -loglevel error -framerate " + std::string(rate) + " -pattern_type glob -i '" +
                          png_dir + "/*.png' -c:v libx264 -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '" + mp4 +
                          "' < /dev/null";
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("ffmpeg could not write '" + mp4 + "' (" + cmd + ")");
}

int runView(const ViewRequest& req, std::ostream& out, std::ostream& err) {
  if (req.isLive()) return runLiveView(req, out, err);
  const auto [w, h] = parseSize(req.size);
  const bool headless = !req.render_png.empty() || !req.sequence_dir.empty() || !req.video.empty();
  const WindowOptions window{w, h, req.script, {}};
  if (!headless) checkWindowRequest(window);
  RecordingCache cache(!req.no_index_cache);  // outlives the model: its private folder holds what the model reads
  if (!cache.note().empty()) err << "roadslam-view: warning: " << cache.note() << "\n";
  ViewerInputs in = req.inputs;
  const RecordingToOpen rec = recordingToOpen(in.recording, cache, err);
  if (rec.rawlog != in.recording) in.source = in.recording;
  in.recording = rec.rawlog;
  if (!rec.damage.empty()) err << "roadslam-view: warning: " << rec.damage << "\n";
  if (req.no_index_cache) in.index.use_cache = false;
  cache.configureIndex(in.index);
  in.index.on_build = [&err, index = in.index](const std::string& path) {
    const std::string kept = std::filesystem::is_directory(path) ? userCacheFolder() : rawlog::RawlogIndex::indexFiles(path, index).write;
    err << "roadslam-view: indexing " << path << " once" << (index.write_cache ? " (kept in " + kept + ")" : "") << " ...\n";
  };
  ViewerModel model(in);
  if (headless) model.waitForIndex();  // renders may need any time of the recording
  for (const auto& warning : model.warnings()) err << "roadslam-view: warning: " << warning << "\n";
  if (const auto lidar = model.lidarModel(); !lidar.warning.empty()) err << "roadslam-view: warning: " << lidar.warning << "\n";
  if (!req.render_png.empty()) {
    const std::string problem = atTimeProblem(req.at_s, model.endTime() - model.startTime(), in.name());
    if (!problem.empty()) {
      err << "roadslam-view: " << problem << "\n";
      return 2;
    }
  }
  out << summaryLine(model) << "\n";
  if (!model.can().empty()) {
    double v_max = 0;
    for (const auto& c : model.can()) v_max = std::isfinite(c.speed_mps) ? std::max(v_max, c.speed_mps) : v_max;
    char line[160];
    std::snprintf(line, sizeof line, "CAN: %zu samples over %.1f s, speed up to %.2f m/s", model.can().size(),
                  model.can().back().t_s - model.can().front().t_s, v_max);
    out << line << "\n";
  }
  std::unique_ptr<LiveSlam> slam;
  if (!req.run_slam_ini.empty()) slam = std::make_unique<LiveSlam>(req.run_slam_ini, in.recording, model);
  Replay replay(model);
  replay.options().color_by = req.color_by;
  replay.options().camera = req.camera;
  if (headless) {
    PngRenderer renderer(w, h);
    if (!req.render_png.empty()) {
      if (slam) {
        slam->waitUntil(model.startTime() + req.at_s);
        model.takePosted();
      }
      replay.seek(model.startTime() + req.at_s);
      renderCurrent(replay, renderer, req.render_png);
      out << req.render_png << ": t = " << req.at_s << " s, observation "
          << (replay.currentObservation() ? std::to_string(*replay.currentObservation()) : "-") << "\n";
    }
    const std::string sequence_dir = !req.sequence_dir.empty() || req.video.empty()
                                         ? req.sequence_dir
                                         : (std::filesystem::temp_directory_path() / ("roadslam_view_video_" + std::to_string(getpid()))).string();
    if (!sequence_dir.empty()) {
      if (slam) {
        slam->waitUntil(1e300);  // the whole recording
        model.takePosted();
      }
      const auto n = renderSequence(replay, renderer, sequence_dir, req.every);
      if (!req.sequence_dir.empty()) out << req.sequence_dir << ": " << n << " pictures\n";
      if (!req.video.empty()) {
        encodeVideo(sequence_dir, req.video, req.fps);
        if (req.sequence_dir.empty()) std::filesystem::remove_all(sequence_dir);
        out << req.video << ": " << n << " frames at " << req.fps << " per second\n";
      }
    }
    if (!replay.lastError().empty()) err << "roadslam-view: warning: " << replay.lastError() << "\n";
    if (slam) {
      out << "odometry (--run-slam): " << slam->frames() << " sweeps, " << model.frames().size() << " frames posted\n";
      if (!slam->error().empty()) err << "roadslam-view: warning: the odometry stopped: " << slam->error() << "\n";
    }
    return 0;
  }
  return runWindow(replay, window, out, err);
}

}  // namespace roadslam::viewer

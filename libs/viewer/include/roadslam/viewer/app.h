#pragma once
/// \file app.h
/// What `roadslam-view` does with its command line: open the model, then render headless
/// (--render / --render-sequence) or open the window (optionally driven by a --script).

#include <ostream>
#include <string>

#include "roadslam/viewer/live_feed.h"
#include "roadslam/viewer/model.h"
#include "roadslam/viewer/scene.h"

namespace roadslam::viewer {

struct ViewRequest {
  ViewerInputs inputs;
  std::string render_png;    ///< --render: the PNG to write
  double at_s = 0;           ///< --at: seconds from the start of the recording
  std::string sequence_dir;  ///< --render-sequence
  std::size_t every = 1;     ///< --every
  std::string size = "1280x720";  ///< WxH [pixels]
  ColorBy color_by = ColorBy::Height;
  CameraMode camera = CameraMode::Follow;
  std::string script;        ///< --script FILE (window)
  std::string video;         ///< --video OUT.mp4: the --render-sequence pictures through ffmpeg
  double fps = 10;           ///< --fps of the video [1/s]
  std::string run_slam_ini;  ///< --run-slam INI: the odometry runs over the recording while it replays
  bool no_index_cache = false;
  LiveRequest live;          ///< --udp / --grab (+ --record): a live view instead of a recording
  std::size_t live_sweeps = 3;    ///< live --render: render once this many sweeps arrived [count]
  double live_timeout_s = 10;     ///< live --render: give up after this long without them [s]
  double live_keep_s = 30;        ///< live: sweeps kept for stepping back [s]
  bool isLive() const { return live.udp_port >= 0 || !live.grab_ini.empty(); }
};

/// Parses "WxH" [pixels]; throws std::invalid_argument naming the text.
std::pair<int, int> parseSize(const std::string& text);

/// One line for a person: observations, duration, how the index was opened, the LiDAR model decoded
/// (ViewerModel::lidarModel), and what the results hold.
std::string summaryLine(ViewerModel& model);

/// Why --at \p at_s [s from the start] cannot be rendered for the recording \p name, \p duration_s
/// long: before its start, or past its end (more than one 10 Hz sweep, 0.1 s, after its last stamp);
/// empty when it can.
std::string atTimeProblem(double at_s, double duration_s, const std::string& name);

/// Encodes DIR/NNNNNN.png (sorted) into \p mp4 at \p fps with ffmpeg (H.264, yuv420p); throws with a
/// clear message when ffmpeg is not installed or fails.
void encodeVideo(const std::string& png_dir, const std::string& mp4, double fps);

/// Runs the request; returns the exit code (0 done, 1 a problem named on \p err, 2 an --at outside
/// the recording).
int runView(const ViewRequest& req, std::ostream& out, std::ostream& err);

/// The live view (req.isLive()): the window follows the sensors; --render writes the newest sweep
/// once req.live_sweeps arrived (exit 1 naming the source when none came within the timeout).
int runLiveView(const ViewRequest& req, std::ostream& out, std::ostream& err);

}  // namespace roadslam::viewer

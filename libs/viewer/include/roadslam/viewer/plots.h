#pragma once
/// \file plots.h
/// The strip of plots under the 3D view: the odometry's per-frame figures over the recording's time
/// (ms per frame, registration inliers; frames that failed or were degenerate marked on top) and the
/// car's CAN speed, yaw rate and steering angle, with a cursor at the replay's time. Drawn into an image (the same in the window and headless renders).

#include <mrpt/img/CImage.h>

#include "roadslam/viewer/model.h"

namespace roadslam::viewer {

/// Colours of the strip (RGB), fixed so tests can find them.
struct PlotColors {
  static constexpr unsigned char ms[3] = {255, 210, 0};       // ms per frame: yellow
  static constexpr unsigned char inliers[3] = {0, 200, 255};  // inliers: cyan
  static constexpr unsigned char failed[3] = {255, 40, 40};   // not converged / empty frames
  static constexpr unsigned char degenerate[3] = {255, 140, 0};
  static constexpr unsigned char cursor[3] = {255, 255, 255};
  static constexpr unsigned char speed[3] = {80, 230, 80};        // CAN speed: green
  static constexpr unsigned char yaw_rate[3] = {210, 130, 255};   // CAN yaw rate: violet, 0 mid-height
  static constexpr unsigned char steering[3] = {255, 110, 170};   // CAN steering angle: pink, 0 mid-height
};

/// A PlotColors entry as an MRPT colour (alpha 255: opaque).
inline mrpt::img::TColor rgb(const unsigned char c[3], unsigned char a = 255) { return {c[0], c[1], c[2], a}; }

/// True when the model has something to plot: frames with figures (a map folder's frames.csv,
/// --run-slam) or CAN signals (--can).
bool hasFramePlots(const ViewerModel& model);

/// The strip, \p width x \p height pixels, for replay time \p t_s.
mrpt::img::CImage framePlots(const ViewerModel& model, double t_s, int width, int height);

}  // namespace roadslam::viewer

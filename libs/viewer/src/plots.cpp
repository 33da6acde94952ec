#include "roadslam/viewer/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace roadslam::viewer {
namespace {

mrpt::img::TColor rgb(const unsigned char c[3]) { return {c[0], c[1], c[2]}; }

double maxOf(const std::vector<FrameResult>& frames, double FrameResult::*field) {
  double m = 0;
  for (const auto& f : frames)
    if (std::isfinite(f.*field)) m = std::max(m, f.*field);
  return m;
}

}  // namespace

bool hasFramePlots(const ViewerModel& model) {
  if (!model.can().empty()) return true;
  for (const auto& f : model.frames())
    if (std::isfinite(f.ms) || std::isfinite(f.inliers)) return true;
  return false;
}

mrpt::img::CImage framePlots(const ViewerModel& model, double t_s, int width, int height) {
  mrpt::img::CImage img(width, height, mrpt::img::CH_RGB);
  img.filledRectangle(0, 0, width - 1, height - 1, mrpt::img::TColor(15, 15, 20));
  const double t0 = model.startTime(), t1 = std::max(model.endTime(), t0 + 1e-6);
  const int left = 4, right = width - 5, top = 18, bottom = height - 4;
  const auto X = [&](double t) { return left + static_cast<int>(std::lround((t - t0) / (t1 - t0) * (right - left))); };
  img.rectangle(left, top, right, bottom, mrpt::img::TColor(70, 70, 80));
  const auto& frames = model.frames();
  const double ms_max = maxOf(frames, &FrameResult::ms), in_max = maxOf(frames, &FrameResult::inliers);
  // One series: a polyline through the frames' values scaled to the strip's height.
  const auto series = [&](double FrameResult::*field, double vmax, const unsigned char c[3]) {
    if (!(vmax > 0)) return;
    int px = -1, py = -1;
    for (const auto& f : frames) {
      if (!std::isfinite(f.*field)) continue;
      const int x = X(f.stamp_s), y = bottom - static_cast<int>(std::lround(f.*field / vmax * (bottom - top - 2)));
      if (px >= 0) img.line(px, py, x, y, rgb(c), 2);
      px = x, py = y;
    }
  };
  series(&FrameResult::inliers, in_max, PlotColors::inliers);
  series(&FrameResult::ms, ms_max, PlotColors::ms);
  // CAN: speed from the bottom, yaw rate around the middle (left turns up)
  double v_max = 0, w_max = 0;
  for (const auto& c : model.can()) {
    if (std::isfinite(c.speed_mps)) v_max = std::max(v_max, std::abs(c.speed_mps));
    if (std::isfinite(c.yaw_rate_rad_s)) w_max = std::max(w_max, std::abs(c.yaw_rate_rad_s));
  }
  const auto canSeries = [&](double CanSample::*field, double vmax, bool centred, const unsigned char c[3]) {
    if (!(vmax > 0)) return;
    int px = -1, py = -1;
    const double span = bottom - top - 2, mid = 0.5 * (top + bottom);
    for (const auto& s : model.can()) {
      if (!std::isfinite(s.*field)) continue;
      const int x = X(s.t_s);
      const int y = centred ? static_cast<int>(std::lround(mid - 0.5 * s.*field / vmax * span))
                            : bottom - static_cast<int>(std::lround(s.*field / vmax * span));
      if (px >= 0) img.line(px, py, x, y, rgb(c), 2);
      px = x, py = y;
    }
  };
  canSeries(&CanSample::speed_mps, v_max, false, PlotColors::speed);
  canSeries(&CanSample::yaw_rate_rad_s, w_max, true, PlotColors::yaw_rate);
  for (const auto& f : frames) {
    const bool failed = f.status == "not_converged" || f.status == "empty";
    if (failed || f.status == "degenerate") {
      const int x = X(f.stamp_s);
      img.line(x, top, x, top + 6, rgb(failed ? PlotColors::failed : PlotColors::degenerate), 1);
    }
  }
  const int xc = X(std::clamp(t_s, t0, t1));
  img.line(xc, top, xc, bottom, rgb(PlotColors::cursor), 1);
  char text[240];
  if (model.can().empty()) {
    std::snprintf(text, sizeof text, "ms/frame (max %.1f)   inliers (max %.0f)   failed | degenerate", ms_max, in_max);
  } else {
    std::snprintf(text, sizeof text, "ms/frame (max %.1f)   inliers (max %.0f)   CAN speed (max %.1f m/s)   yaw rate (max %.1f deg/s)",
                  ms_max, in_max, v_max, w_max * 180.0 / M_PI);
  }
  img.textOut(left + 2, 3, text, mrpt::img::TColor(220, 220, 220));
  return img;
}

}  // namespace roadslam::viewer

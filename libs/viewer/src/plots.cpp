#include "roadslam/viewer/plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace roadslam::viewer {
namespace {


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
  // One series: a polyline through (time, value) scaled to the strip's height, from the bottom or,
  // centred, around the middle (signed values: left turns up). The scale is the largest value but
  // at least \p floor, so a straight drive's noise stays a flat line.
  const auto series = [&](const std::vector<std::pair<double, double>>& tv, bool centred, const unsigned char c[3],
                          double floor = 0.0) {
    double vmax = 0;
    for (const auto& [t, v] : tv) vmax = std::max(vmax, std::abs(v));
    if (!(vmax > 0)) return 0.0;
    const double scale = std::max(vmax, floor);
    const double span = bottom - top - 2, mid = 0.5 * (top + bottom);
    int px = -1, py = -1;
    for (const auto& [t, v] : tv) {
      const int x = X(t), y = static_cast<int>(std::lround(centred ? mid - 0.5 * v / scale * span : bottom - v / scale * span));
      if (px >= 0) img.line(px, py, x, y, rgb(c), 2);
      px = x, py = y;
    }
    return vmax;
  };
  const auto ofFrames = [&](double ViewerFrame::*field) {
    std::vector<std::pair<double, double>> tv;
    for (const auto& f : frames)
      if (std::isfinite(f.*field)) tv.emplace_back(f.stamp_s, f.*field);
    return tv;
  };
  const auto ofCan = [&](double CanSample::*field) {
    std::vector<std::pair<double, double>> tv;
    for (const auto& c : model.can())
      if (std::isfinite(c.*field)) tv.emplace_back(c.t_s, c.*field);
    return tv;
  };
  const double in_max = series(ofFrames(&ViewerFrame::inliers), false, PlotColors::inliers);
  const double ms_max = series(ofFrames(&ViewerFrame::ms), false, PlotColors::ms);
  const double v_max = series(ofCan(&CanSample::speed_mps), false, PlotColors::speed);
  // full scale at least a brisk turn: 0.3 rad/s (17 deg/s) of yaw rate, 0.3 rad of steering
  const double w_max = series(ofCan(&CanSample::yaw_rate_rad_s), true, PlotColors::yaw_rate, 0.3);
  const double d_max = series(ofCan(&CanSample::steering_rad), true, PlotColors::steering, 0.3);
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
    std::snprintf(text, sizeof text,
                  "ms/frame (max %.1f)   inliers (max %.0f)   CAN speed (max %.1f m/s)   yaw rate (max %.1f deg/s)"
                  "   steering (max %.1f deg)",
                  ms_max, in_max, v_max, w_max * 180.0 / M_PI, d_max * 180.0 / M_PI);
  }
  img.textOut(left + 2, 3, text, mrpt::img::TColor(220, 220, 220));
  return img;
}

}  // namespace roadslam::viewer

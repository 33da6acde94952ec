#pragma once
/// \file svg_plot.h
/// Line and scatter plots as inline SVG: axes with "nice" ticks (1, 2, 5 x 10^k), one colour per
/// series from a fixed palette, a legend, and optional vertical markers (e.g. gaps in a recording).

#include <string>
#include <vector>

namespace roadslam::report {

struct Series {
  std::string name;
  std::vector<double> x, y;  ///< same length; non-finite points are left out
};

struct PlotOptions {
  std::string title, x_label, y_label;
  int width_px = 640, height_px = 320;
  bool lines = true;   ///< join the points of a series
  bool points = true;  ///< mark each point
  std::vector<double> x_markers;  ///< vertical lines at these x (drawn in grey)
  bool y_include_zero = false;  ///< the y range reaches down (or up) to 0 (rates, counts)
  bool equal_axes = false;  ///< one unit is as long on x as on y (paths in metres); ranges widen to fit
};

/// The palette's colour of series \p i ("#1f77b4", ...), for legends drawn elsewhere.
std::string seriesColour(size_t i);
/// Tick values covering [lo, hi], about \p target of them, at 1, 2 or 5 x 10^k steps.
std::vector<double> niceTicks(double lo, double hi, int target = 6);
/// The plot; an empty plot (no finite point) says so in its frame.
std::string svgPlot(const std::vector<Series>& series, const PlotOptions& opt);

}  // namespace roadslam::report

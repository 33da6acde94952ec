#include "roadslam/report/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "roadslam/report/html_page.h"

namespace roadslam::report {
namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

std::string label(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return b;
}

}  // namespace

std::string seriesColour(size_t i) {
  // Tableau 10, readable on white and for most colour-blind readers.
  static const char* k[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                            "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return k[i % 10];
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  if (!(hi > lo)) return {lo};
  const double raw = (hi - lo) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * mag;
    if (step >= raw) break;
  }
  std::vector<double> t;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) t.push_back(v);
  return t;
}

std::string svgPlot(const std::vector<Series>& series, const PlotOptions& o) {
  const double W = o.width_px, H = o.height_px, l = 64, r = 16, t = 28, b = 44;
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, y0 = x0, y1 = -x0;
  for (const auto& s : series) {
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      x0 = std::min(x0, s.x[i]), x1 = std::max(x1, s.x[i]), y0 = std::min(y0, s.y[i]), y1 = std::max(y1, s.y[i]);
    }
  }
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(W) + "\" height=\"" + num(H) +
                    "\" font-family=\"sans-serif\" font-size=\"11\">\n<rect x=\"0\" y=\"0\" width=\"" + num(W) +
                    "\" height=\"" + num(H) + "\" fill=\"white\"/>\n<text x=\"" + num(W / 2) +
                    "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" + htmlEscape(o.title) + "</text>\n";
  if (!std::isfinite(x0)) {
    return svg + "<text x=\"" + num(W / 2) + "\" y=\"" + num(H / 2) + "\" text-anchor=\"middle\">no data</text>\n</svg>";
  }
  if (o.y_include_zero) y0 = std::min(y0, 0.0), y1 = std::max(y1, 0.0);
  if (x1 - x0 < 1e-12) x0 -= 0.5, x1 += 0.5;
  if (y1 - y0 < 1e-12) y0 -= 0.5, y1 += 0.5;
  const double pad = 0.05 * (y1 - y0);
  y0 -= pad, y1 += pad;
  if (o.equal_axes) {  // widen the range that has fewer units per pixel, about its centre
    const double ux = (x1 - x0) / (W - l - r), uy = (y1 - y0) / (H - t - b), u = std::max(ux, uy);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1), hx = 0.5 * u * (W - l - r), hy = 0.5 * u * (H - t - b);
    x0 = cx - hx, x1 = cx + hx, y0 = cy - hy, y1 = cy + hy;
  }
  const auto X = [&](double v) { return l + (v - x0) / (x1 - x0) * (W - l - r); };
  const auto Y = [&](double v) { return H - b - (v - y0) / (y1 - y0) * (H - t - b); };
  for (double v : niceTicks(x0, x1)) {
    svg += "<line x1=\"" + num(X(v)) + "\" y1=\"" + num(t) + "\" x2=\"" + num(X(v)) + "\" y2=\"" + num(H - b) +
           "\" stroke=\"#eee\"/><text x=\"" + num(X(v)) + "\" y=\"" + num(H - b + 14) + "\" text-anchor=\"middle\">" +
           label(v) + "</text>\n";
  }
  for (double v : niceTicks(y0, y1, 5)) {
    svg += "<line x1=\"" + num(l) + "\" y1=\"" + num(Y(v)) + "\" x2=\"" + num(W - r) + "\" y2=\"" + num(Y(v)) +
           "\" stroke=\"#eee\"/><text x=\"" + num(l - 4) + "\" y=\"" + num(Y(v) + 4) + "\" text-anchor=\"end\">" +
           label(v) + "</text>\n";
  }
  for (double m : o.x_markers) {
    if (m < x0 || m > x1) continue;
    svg += "<line x1=\"" + num(X(m)) + "\" y1=\"" + num(t) + "\" x2=\"" + num(X(m)) + "\" y2=\"" + num(H - b) +
           "\" stroke=\"#999\" stroke-dasharray=\"3,3\"/>\n";
  }
  svg += "<rect x=\"" + num(l) + "\" y=\"" + num(t) + "\" width=\"" + num(W - l - r) + "\" height=\"" + num(H - t - b) +
         "\" fill=\"none\" stroke=\"#888\"/>\n";
  svg += "<text x=\"" + num(l + (W - l - r) / 2) + "\" y=\"" + num(H - 8) + "\" text-anchor=\"middle\">" +
         htmlEscape(o.x_label) + "</text>\n<text transform=\"translate(14," + num(t + (H - t - b) / 2) +
         ") rotate(-90)\" text-anchor=\"middle\">" + htmlEscape(o.y_label) + "</text>\n";
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    const std::string c = seriesColour(k);
    std::string path;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      path += (path.empty() ? "M" : " L") + num(X(s.x[i])) + "," + num(Y(s.y[i]));
      if (o.points) svg += "<circle cx=\"" + num(X(s.x[i])) + "\" cy=\"" + num(Y(s.y[i])) + "\" r=\"3\" fill=\"" + c + "\"/>\n";
    }
    if (o.lines && !path.empty()) svg += "<path d=\"" + path + "\" fill=\"none\" stroke=\"" + c + "\" stroke-width=\"1.5\"/>\n";
    svg += "<rect x=\"" + num(l + 8) + "\" y=\"" + num(t + 6 + 14 * k) + "\" width=\"10\" height=\"10\" fill=\"" + c +
           "\"/><text x=\"" + num(l + 22) + "\" y=\"" + num(t + 15 + 14 * k) + "\">" + htmlEscape(s.name) + "</text>\n";
  }
  return svg + "</svg>";
}

}  // namespace roadslam::report

#include "roadslam/eval/plot.h"

#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::eval {
namespace {

using mrpt::img::TColor;

constexpr int kWidth = 900;
constexpr int kMapHeight = 700;
constexpr int kErrHeight = 260;
constexpr int kMargin = 50;

struct Box {
  double x0, y0, x1, y1;  ///< data range
  int px0, py0, px1, py1; ///< pixel rectangle (py0 top)
  int u(double x) const { return px0 + static_cast<int>((x - x0) / (x1 - x0) * (px1 - px0)); }
  int v(double y) const { return py1 - static_cast<int>((y - y0) / (y1 - y0) * (py1 - py0)); }
};

Box equalAxesBox(const MatchedTrajectories& m, const Eigen::Isometry3d& T) {
  double x0 = 1e18, y0 = 1e18, x1 = -1e18, y1 = -1e18;
  auto grow = [&](const Eigen::Vector3d& p) {
    x0 = std::min(x0, p.x()); x1 = std::max(x1, p.x());
    y0 = std::min(y0, p.y()); y1 = std::max(y1, p.y());
  };
  for (size_t i = 0; i < m.gt.size(); ++i) {
    grow(m.gt[i].translation());
    grow(T * m.est[i].translation());
  }
  const int pw = kWidth - 2 * kMargin, ph = kMapHeight - 2 * kMargin;
  const double span = std::max({(x1 - x0) / pw, (y1 - y0) / ph, 1e-3}) * 1.05;
  const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  return {cx - span * pw / 2, cy - span * ph / 2, cx + span * pw / 2, cy + span * ph / 2,
          kMargin, kMargin, kMargin + pw, kMargin + ph};
}

template <class F>
void polyline(mrpt::img::CImage& img, const Box& b, size_t n, F&& xy, TColor c) {
  for (size_t i = 1; i < n; ++i) {
    const auto p = xy(i - 1), q = xy(i);
    img.line(b.u(p.x()), b.v(p.y()), b.u(q.x()), b.v(q.y()), c, 2);
  }
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

void plotTrajectories(const std::string& path, const MatchedTrajectories& m,
                      const TrajectoryMetrics& metrics, const std::string& title) {
  const TColor white(255, 255, 255), black(0, 0, 0), grey(200, 200, 200);
  const TColor gt_col(30, 30, 30), est_col(220, 50, 40), err_col(40, 90, 200);
  mrpt::img::CImage img(kWidth, kMapHeight + kErrHeight, mrpt::img::CH_RGB);
  img.filledRectangle(0, 0, kWidth - 1, kMapHeight + kErrHeight - 1, white);

  const Box map = equalAxesBox(m, metrics.T_gt_est);
  img.rectangle(map.px0, map.py0, map.px1, map.py1, grey);
  polyline(img, map, m.gt.size(), [&](size_t i) { return Eigen::Vector3d(m.gt[i].translation()); }, gt_col);
  polyline(img, map, m.est.size(),
           [&](size_t i) { return Eigen::Vector3d(metrics.T_gt_est * m.est[i].translation()); }, est_col);
  img.selectTextFont("9x15");
  img.textOut(kMargin, 12, title, black);
  img.textOut(kMargin, 28, "ground truth (black), estimate aligned SE(3) (red); top view, equal axes", black);
  img.textOut(map.px0 + 4, map.py1 - 18,
              fmt("scale: %.1f m across", map.x1 - map.x0), black);

  const double dmax = std::max(metrics.distance_m.back(), 1e-6);
  const double emax = std::max(*std::max_element(metrics.ate_error_m.begin(), metrics.ate_error_m.end()), 1e-3);
  const Box err{0, 0, dmax, emax * 1.1, kMargin, kMapHeight + 30, kWidth - kMargin, kMapHeight + kErrHeight - 40};
  img.rectangle(err.px0, err.py0, err.px1, err.py1, grey);
  polyline(img, err, metrics.ate_error_m.size(),
           [&](size_t i) { return Eigen::Vector3d(metrics.distance_m[i], metrics.ate_error_m[i], 0); }, err_col);
  img.textOut(err.px0, err.py0 - 18,
              "position error after alignment [m] vs distance [m]: ATE RMSE " +
                  fmt("%.3f m", metrics.ate_rmse_m) + ", RTE " + fmt("%.2f %%", metrics.rte_percent),
              black);
  img.textOut(err.px0, err.py1 + 6, "0", black);
  img.textOut(err.px1 - 60, err.py1 + 6, fmt("%.1f m", dmax), black);
  img.textOut(err.px0 + 4, err.py0 + 4, fmt("%.3f m", emax * 1.1), black);

  // CImage picks the format from the extension, so the temporary keeps ".png" at its end.
  const std::string tmp = tempPathFor(path) + ".png";
  if (!img.saveToFile(tmp)) throw std::runtime_error("cannot write plot '" + path + "'");
  commitTempFile(tmp, path);
}

}  // namespace roadslam::eval

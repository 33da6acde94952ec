#include <cerrno>
#include <mrpt/img/CImage.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/mapping/maps.h"

namespace roadslam::mapping {
namespace {

/// Blue (low) -> green -> red (high) for t in [0, 1].
mrpt::img::TColor heightColour(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const auto u = [](double v) { return static_cast<uint8_t>(std::clamp(v, 0.0, 1.0) * 255); };
  return mrpt::img::TColor(u(2 * t - 1), u(1 - std::abs(2 * t - 1)), u(1 - 2 * t));
}

}  // namespace

void drawTopView(const std::string& png_path, const std::vector<Eigen::Vector3f>& pts, const PoseVector& traj,
                 const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& loops, int max_px,
                 const std::vector<TopViewBox>& boxes) {
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  for (const auto& T : traj) {
    lo = lo.cwiseMin(T.translation().head<2>());
    hi = hi.cwiseMax(T.translation().head<2>());
  }
  std::vector<float> zs;
  for (const auto& p : pts) zs.push_back(p.z());
  if (traj.empty()) lo = hi = Eigen::Vector2d::Zero();
  lo -= Eigen::Vector2d::Constant(30);  // the map reaches beyond the trajectory
  hi += Eigen::Vector2d::Constant(30);
  const double scale = max_px / std::max(hi.x() - lo.x(), hi.y() - lo.y());  // [px/m]
  const int w = std::max(64, static_cast<int>((hi.x() - lo.x()) * scale));
  const int h = std::max(64, static_cast<int>((hi.y() - lo.y()) * scale)) + 40;  // 40 px text band
  mrpt::img::CImage img(w, h, mrpt::img::CH_RGB);
  img.filledRectangle(0, 0, w - 1, h - 1, mrpt::img::TColor(20, 20, 20));
  const auto px = [&](const Eigen::Vector2d& m) {
    return Eigen::Vector2i(static_cast<int>((m.x() - lo.x()) * scale), h - 40 - static_cast<int>((m.y() - lo.y()) * scale));
  };
  double z0 = 0, z1 = 1;
  if (!zs.empty()) {  // colour range: 2nd to 98th percentile of the heights
    std::sort(zs.begin(), zs.end());
    z0 = zs[zs.size() / 50];
    z1 = std::max(zs[zs.size() * 49 / 50], static_cast<float>(z0 + 0.5));
  }
  for (const auto& p : pts) {
    const auto q = px(p.cast<double>().head<2>());
    if (q.x() >= 0 && q.y() >= 0 && q.x() < w && q.y() < h - 40) img.setPixel(q.x(), q.y(), heightColour((p.z() - z0) / (z1 - z0)));
  }
  for (size_t i = 1; i < traj.size(); ++i) {
    const auto a = px(traj[i - 1].translation().head<2>()), b = px(traj[i].translation().head<2>());
    img.line(a.x(), a.y(), b.x(), b.y(), mrpt::img::TColor(255, 255, 255), 2);
  }
  for (const auto& [a3, b3] : loops) {
    const auto a = px(a3.head<2>()), b = px(b3.head<2>());
    img.line(a.x(), a.y(), b.x(), b.y(), mrpt::img::TColor(255, 0, 255), 2);
    img.drawCircle(a.x(), a.y(), 6, mrpt::img::TColor(255, 0, 255), 2);
  }
  const mrpt::img::TColor yellow(255, 220, 0);
  for (const TopViewBox& b : boxes) {
    const auto c = b.box.corners();
    for (int k = 0; k < 4; ++k) {
      const auto a = px(c[k]), e = px(c[(k + 1) % 4]);
      img.line(a.x(), a.y(), e.x(), e.y(), yellow, 2);
    }
    // velocity arrow: 1 s of travel, head 30 deg either side
    const Eigen::Vector2d& centre = b.box.centre_m;
    const auto a = px(centre), e = px(centre + b.velocity);
    img.line(a.x(), a.y(), e.x(), e.y(), yellow, 2);
    const double speed = b.velocity.norm();
    if (speed > 0.5) {
      const Eigen::Vector2d d = b.velocity / speed, n(-d.y(), d.x()), tip = centre + b.velocity;
      const double head = std::min(2.0, 0.3 * speed);
      for (double side : {-1.0, 1.0}) {
        const auto h = px(tip - head * (std::cos(M_PI / 6) * d + side * std::sin(M_PI / 6) * n));
        img.line(e.x(), e.y(), h.x(), h.y(), yellow, 2);
      }
    }
    img.textOut(a.x() + 6, a.y() - 14, std::to_string(b.id), yellow);
  }
  const int bar_px = static_cast<int>(50 * scale);  // 50 m scale bar
  img.filledRectangle(10, h - 25, 10 + bar_px, h - 20, mrpt::img::TColor(255, 255, 255));
  img.textOut(15 + bar_px, h - 32, "50 m   white: trajectory, magenta: " + std::to_string(loops.size()) +
                                       " loop closures, points coloured by height" +
                                       (boxes.empty() ? std::string() : ", yellow: moving tracks (last box, id, 1 s arrow)"),
              mrpt::img::TColor(255, 255, 255));
  TempFile tmp(png_path, ".png");
  errno = 0;
  if (!img.saveToFile(tmp.path())) throw std::runtime_error(tmp.failure("top view"));
  tmp.commit();
}

}  // namespace roadslam::mapping

#include "roadslam/objects/free_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadslam::objects {
namespace {

// Sweeps without ring ids (KITTI .bin) take elevation bins for rings: 0.4 deg, the HDL-64E's mean
// spacing (26.9 deg over 64 beams; Velodyne HDL-64E S2 manual)
constexpr double kElevationBin_rad = 0.4 * M_PI / 180;
constexpr double kLowestElevation_rad = -30.0 * M_PI / 180;
constexpr int kElevationBins = 150;  // -30 to +30 deg

int column(double x, double y, int bins) {
  const double az = std::atan2(y, x) + M_PI;  // [0, 2 pi]
  return std::min(bins - 1, static_cast<int>(az / (2 * M_PI) * bins));
}

/// The ring whose beam elevation is nearest \p el, -1 when \p el lies farther than half the spacing
/// to the next beam (between two beams: no ray went there).
int ringOf(const std::vector<double>& elevation, double el) {
  int best = -1;
  double best_d = std::numeric_limits<double>::max();
  for (size_t r = 0; r < elevation.size(); ++r) {
    if (!std::isfinite(elevation[r])) continue;
    const double d = std::abs(el - elevation[r]);
    if (d < best_d) best_d = d, best = static_cast<int>(r);
  }
  if (best < 0) return -1;
  double spacing = std::numeric_limits<double>::max();
  for (size_t r = 0; r < elevation.size(); ++r) {
    if (static_cast<int>(r) != best && std::isfinite(elevation[r]))
      spacing = std::min(spacing, std::abs(elevation[r] - elevation[static_cast<size_t>(best)]));
  }
  return best_d <= 0.5 * spacing ? best : -1;
}

}  // namespace

void FreeSpaceHistory::add(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double t_s) {
  while (!sweeps_.empty() && (sweeps_.front().t < t_s - keep_s_ || sweeps_.front().t > t_s)) sweeps_.pop_front();
  if (scan.points.empty() || !T_map_lidar.matrix().allFinite()) return;
  int rings = kElevationBins;
  if (scan.has_rings) {
    rings = 0;
    for (const ScanPoint& q : scan.points) rings = std::max(rings, static_cast<int>(q.ring) + 1);
  }
  Sweep s;
  s.t = t_s;
  s.T_lidar_map = T_map_lidar.inverse();
  s.range.assign(static_cast<size_t>(rings) * bins_, 0.f);
  std::vector<double> el_sum(static_cast<size_t>(rings), 0.0);
  std::vector<int> el_n(static_cast<size_t>(rings), 0);
  for (const ScanPoint& q : scan.points) {
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) continue;
    const double xy = std::hypot(q.x, q.y), r = std::hypot(xy, double(q.z));
    if (r < 0.5) continue;
    const double el = std::atan2(double(q.z), xy);
    const int ring = scan.has_rings ? q.ring : static_cast<int>(std::floor((el - kLowestElevation_rad) / kElevationBin_rad));
    if (ring < 0 || ring >= rings) continue;
    el_sum[static_cast<size_t>(ring)] += el, ++el_n[static_cast<size_t>(ring)];
    float& cell = s.range[static_cast<size_t>(ring) * bins_ + column(q.x, q.y, bins_)];
    if (cell == 0.f || r < cell) cell = static_cast<float>(r);
  }
  s.ring_elevation.resize(static_cast<size_t>(rings));
  for (size_t k = 0; k < el_sum.size(); ++k) s.ring_elevation[k] = el_n[k] ? el_sum[k] / el_n[k] : NAN;
  sweeps_.push_back(std::move(s));
}

FreeEvidence FreeSpaceHistory::check(const std::vector<Eigen::Vector3d>& pts_map, double t_s, double lag_s,
                                     double margin_m) const {
  FreeEvidence e;
  const Sweep* best = nullptr;
  for (const Sweep& s : sweeps_) {
    if (!best || std::abs(s.t - (t_s - lag_s)) < std::abs(best->t - (t_s - lag_s))) best = &s;
  }
  if (!best || std::abs(best->t - (t_s - lag_s)) > 0.5 * lag_s) return e;
  for (const Eigen::Vector3d& p_map : pts_map) {
    const Eigen::Vector3d p = best->T_lidar_map * p_map;
    const double xy = std::hypot(p.x(), p.y()), r = p.norm();
    const int ring = ringOf(best->ring_elevation, std::atan2(p.z(), xy));
    if (ring < 0) continue;
    const float seen = best->range[static_cast<size_t>(ring) * bins_ + column(p.x(), p.y(), bins_)];
    if (seen == 0.f) continue;  // no return: the ray's end is unknown
    if (seen > r + margin_m) {
      ++e.through;
    } else if (seen >= r - margin_m) {
      ++e.hit;
    }  // nearer: something hid the place then
  }
  return e;
}

}  // namespace roadslam::objects

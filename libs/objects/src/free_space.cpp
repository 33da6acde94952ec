#include "roadslam/objects/free_space.h"

#include "range_image.h"

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
    float& cell = s.range[static_cast<size_t>(ring) * bins_ + detail::azimuthColumn(double(q.x), double(q.y), bins_)];
    if (cell == 0.f || r < cell) cell = static_cast<float>(r);
  }
  // the beams by elevation, each owning the elevations within half its nearest neighbour's gap (a
  // direction farther from every beam than that lies between two: no ray went there)
  for (size_t k = 0; k < el_sum.size(); ++k) {
    if (el_n[k]) s.beams.push_back({el_sum[k] / el_n[k], 0, 0, static_cast<int>(k)});
  }
  std::sort(s.beams.begin(), s.beams.end(), [](const Beam& a, const Beam& b) { return a.elevation < b.elevation; });
  for (size_t k = 0; k < s.beams.size(); ++k) {
    double gap = std::numeric_limits<double>::max();
    if (k > 0) gap = std::min(gap, s.beams[k].elevation - s.beams[k - 1].elevation);
    if (k + 1 < s.beams.size()) gap = std::min(gap, s.beams[k + 1].elevation - s.beams[k].elevation);
    s.beams[k].lo = s.beams[k].elevation - 0.5 * gap, s.beams[k].hi = s.beams[k].elevation + 0.5 * gap;
  }
  sweeps_.push_back(std::move(s));
}

int FreeSpaceHistory::Sweep::ringAt(double el) const {
  const auto it = std::upper_bound(beams.begin(), beams.end(), el, [](double e, const Beam& b) { return e < b.hi; });
  return it != beams.end() && el >= it->lo ? it->ring : -1;
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
    const int ring = best->ringAt(std::atan2(p.z(), xy));
    if (ring < 0) continue;
    const float seen = best->range[static_cast<size_t>(ring) * bins_ + detail::azimuthColumn(p.x(), p.y(), bins_)];
    if (seen == 0.f) continue;  // no return: the ray's end is unknown
    if (seen > r + margin_m) {
      ++e.through;
    } else if (seen >= r - margin_m) {
      ++e.hit;
    }  // nearer: something hid the place then
  }
  return e;
}

std::vector<Eigen::Vector3d> samplePointsInMap(const Scan& scan, const std::vector<uint32_t>& indices,
                                               const Eigen::Isometry3d& T_map_lidar, size_t max_points) {
  std::vector<Eigen::Vector3d> out;
  const size_t stride = std::max<size_t>(1, indices.size() / std::max<size_t>(1, max_points));
  for (size_t k = 0; k < indices.size(); k += stride) {
    const ScanPoint& q = scan.points[indices[k]];
    out.push_back(T_map_lidar * Eigen::Vector3d(q.x, q.y, q.z));
  }
  return out;
}

}  // namespace roadslam::objects

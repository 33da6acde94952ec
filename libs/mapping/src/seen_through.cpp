#include "roadslam/mapping/seen_through.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "ini_keys.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "roadslam/mapping/mapper.h"

namespace roadslam::mapping {
namespace {

using VoxelSet = std::unordered_set<Eigen::Vector3i, VoxelKeyHash>;

Eigen::Vector3i voxelOf(const Eigen::Vector3f& p, double voxel_m) {
  return (p / static_cast<float>(voxel_m)).array().floor().cast<int>().matrix();
}

/// A tested voxel: its first point (map frame) and the references' votes.
struct Cell {
  Eigen::Vector3i key;
  Eigen::Vector3f point;
  int through = 0, hits = 0;
};

/// Nearest range per pixel of one sweep (lidar frame), elevation within +-kMaxElevation; 0 = no return.
class RangeImage {
 public:
  static constexpr double kMaxElevation = 1.2;  // [rad] (69 deg: above any automotive lidar's field of view)

  explicit RangeImage(const SeenThroughParams& p)
      : az_res_(p.azimuth_res_rad), el_res_(p.elevation_res_rad),
        cols_(static_cast<int>(std::ceil(2 * M_PI / az_res_))),
        rows_(static_cast<int>(std::ceil(2 * kMaxElevation / el_res_))),
        range_(static_cast<size_t>(cols_) * rows_, 0.0f), slope_(range_.size(), 0.0f) {}

  void fill(const std::vector<Eigen::Vector3f>& points_lidar) {
    std::fill(range_.begin(), range_.end(), 0.0f);
    for (const auto& q : points_lidar) {
      int row = 0, col = 0;
      const float r = q.norm();
      if (!pixel(q, r, row, col)) continue;
      const size_t i = static_cast<size_t>(row) * cols_ + col;
      const float slope = q.z() / std::max(1e-3f, q.head<2>().norm());
      if (range_[i] == 0.0f || r < range_[i]) {
        range_[i] = r;
        slope_[i] = slope;
      }
    }
  }

  /// Spherical projection (azimuth atan2(y, x), elevation asin(z / r)); false outside the image.
  bool pixel(const Eigen::Vector3f& q, float r, int& row, int& col) const {
    if (r < 1e-3f) return false;
    const double el = std::asin(std::clamp(q.z() / r, -1.0f, 1.0f));
    if (std::abs(el) >= kMaxElevation) return false;
    row = static_cast<int>((el + kMaxElevation) / el_res_);
    col = static_cast<int>((std::atan2(q.y(), q.x()) + M_PI) / az_res_);
    row = std::min(row, rows_ - 1);
    col = std::min(col, cols_ - 1);
    return true;
  }

  float at(int row, int col) const { return range_[index(row, col)]; }
  /// The pixel's ray: height gained per metre of horizontal distance (tan of its elevation) [-]
  float slope(int row, int col) const { return slope_[index(row, col)]; }

 private:
  size_t index(int row, int col) const { return static_cast<size_t>(row) * cols_ + ((col % cols_) + cols_) % cols_; }

  double az_res_, el_res_;
  int cols_, rows_;
  std::vector<float> range_, slope_;
};

/// Map voxels of the keyframes, and the ground height per x-y cell (lowest point).
std::vector<Cell> testedCells(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, double voxel_m,
                              const SeenThroughParams& p, SeenThroughStats& st) {
  std::unordered_map<Eigen::Vector3i, Eigen::Vector3f, VoxelKeyHash> voxels;
  std::unordered_map<Eigen::Vector3i, float, VoxelKeyHash> ground;  // key (cx, cy, 0)
  const float cell = static_cast<float>(p.ground_cell_m);
  auto cellOf = [&](const Eigen::Vector3f& q) {
    return Eigen::Vector3i(static_cast<int>(std::floor(q.x() / cell)), static_cast<int>(std::floor(q.y() / cell)), 0);
  };
  for (size_t k = 0; k < kfs.size() && k < T_map_kf.size(); ++k) {
    const Eigen::Isometry3f T = T_map_kf[k].cast<float>();
    for (const auto& q : kfs[k].points_lidar) {
      const Eigen::Vector3f m = T * q;
      voxels.emplace(voxelOf(m, voxel_m), m);
      auto [it, fresh] = ground.emplace(cellOf(m), m.z());
      if (!fresh) it->second = std::min(it->second, m.z());
    }
  }
  st.voxels = voxels.size();
  std::vector<Cell> cells;
  for (const auto& [key, m] : voxels) {
    if (p.min_height_m <= 0 || m.z() - ground.at(cellOf(m)) >= p.min_height_m) cells.push_back({key, m});
  }
  // a fixed order (the hash map's is not): the votes do not depend on it, the output set neither
  std::sort(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) {
    return std::lexicographical_compare(a.key.data(), a.key.data() + 3, b.key.data(), b.key.data() + 3);
  });
  st.tested_voxels = cells.size();
  return cells;
}

/// One reference's votes on the cells within max_range_m of its lidar (bucketed by x-y tiles).
void vote(const RangeImage& img, const Eigen::Isometry3f& T_lidar_map, const SeenThroughParams& p,
          std::vector<Cell>& cells, const std::vector<size_t>& candidates) {
  const float max_r = static_cast<float>(p.max_range_m);
  for (size_t i : candidates) {
    Cell& c = cells[i];
    const Eigen::Vector3f q = T_lidar_map * c.point;
    const float r = q.norm();
    int row = 0, col = 0;
    if (r > max_r || !img.pixel(q, r, row, col)) continue;
    const float m = img.at(row, col), slope = img.slope(row, col);
    if (m == 0.0f) continue;  // no return (beyond the reach, absorbed, a hole of the keyframe's voxel grid): nothing known
    const float margin = static_cast<float>(p.margin_m + p.margin_ratio * r);
    if (std::abs(m - r) <= margin) {
      ++c.hits;
      continue;
    }
    if (m < r) continue;  // occluded: says nothing
    // The ray must pass through the voxel, not over it: at grazing incidence a ray a fraction of a
    // pixel above a ground point meets the ground metres behind it.
    if (std::abs(q.head<2>().norm() * slope - q.z()) > p.ray_tolerance_m) continue;
    bool through = true;
    for (int d = 1; d <= p.azimuth_window && through; ++d) {
      for (int s : {-d, d}) {
        const float n = img.at(row, col + s);
        if (n != 0.0f && n <= r + margin) through = false;
      }
    }
    if (through) ++c.through;
  }
}

}  // namespace

void SeenThroughParams::fields(ParamTable& t) {
  t.flag("enabled", enabled);
  t.angle("azimuth_res_deg", azimuth_res_rad);
  t.angle("elevation_res_deg", elevation_res_rad);
  t.num("azimuth_window", azimuth_window);
  t.num("margin_m", margin_m);
  t.num("margin_ratio", margin_ratio);
  t.num("ray_tolerance_m", ray_tolerance_m);
  t.num("max_range_m", max_range_m);
  t.num("min_height_m", min_height_m);
  t.num("ground_cell_m", ground_cell_m);
  t.num("reference_spacing_m", reference_spacing_m);
  t.num("min_through", min_through);
  t.num("through_hit_ratio", through_hit_ratio);
}

void SeenThroughParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<SeenThroughParams>());
  requireValues(cfg, s, {{"azimuth_res_deg", azimuth_res_rad > 0, "> 0"},
                          {"elevation_res_deg", elevation_res_rad > 0, "> 0"},
                          {"azimuth_window", azimuth_window >= 0, ">= 0"},
                          {"margin_m", margin_m >= 0, ">= 0"},
                          {"margin_ratio", margin_ratio >= 0, ">= 0"},
                          {"ray_tolerance_m", ray_tolerance_m > 0, "> 0"},
                          {"max_range_m", max_range_m > 0, "> 0"},
                          {"ground_cell_m", ground_cell_m > 0, "> 0"},
                          {"reference_spacing_m", reference_spacing_m >= 0, ">= 0"},
                          {"min_through", min_through >= 1, ">= 1"},
                          {"through_hit_ratio", through_hit_ratio >= 0, ">= 0"}});
}

void SeenThroughParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

VoxelSet findSeenThrough(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, double voxel_m,
                         const SeenThroughParams& p, SeenThroughStats* stats) {
  const auto t0 = std::chrono::steady_clock::now();
  SeenThroughStats st;
  std::vector<Cell> cells = testedCells(kfs, T_map_kf, voxel_m, p, st);
  // x-y tiles of max_range_m: a reference tests the cells of the 3 x 3 tiles around its own
  const double tile = p.max_range_m;
  auto tileOf = [&](double x, double y) {
    return Eigen::Vector3i(static_cast<int>(std::floor(x / tile)), static_cast<int>(std::floor(y / tile)), 0);
  };
  std::unordered_map<Eigen::Vector3i, std::vector<size_t>, VoxelKeyHash> tiles;
  for (size_t i = 0; i < cells.size(); ++i) tiles[tileOf(cells[i].point.x(), cells[i].point.y())].push_back(i);
  RangeImage img(p);
  std::vector<size_t> candidates;
  double last_path = -1e18;
  for (size_t k = 0; k < kfs.size() && k < T_map_kf.size(); ++k) {
    if (kfs[k].path_m - last_path < p.reference_spacing_m) continue;
    last_path = kfs[k].path_m;
    ++st.references;
    img.fill(kfs[k].points_lidar);
    const Eigen::Vector3d o = T_map_kf[k].translation();
    const Eigen::Vector3i t = tileOf(o.x(), o.y());
    candidates.clear();
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = tiles.find(t + Eigen::Vector3i(dx, dy, 0));
        if (it != tiles.end()) candidates.insert(candidates.end(), it->second.begin(), it->second.end());
      }
    }
    vote(img, T_map_kf[k].inverse().cast<float>(), p, cells, candidates);
  }
  VoxelSet dynamic;
  for (const Cell& c : cells) {
    if (c.through >= p.min_through && c.through > p.through_hit_ratio * c.hits) dynamic.insert(c.key);
  }
  st.dynamic_voxels = dynamic.size();
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (stats) *stats = st;
  return dynamic;
}

SeenThroughStats removeSeenThrough(Mapper& mapper, double voxel_m, const SeenThroughParams& p) {
  SeenThroughStats st;
  const PoseVector T_map_kf = mapper.keyframePoses();
  const VoxelSet dynamic = findSeenThrough(mapper.keyframes(), T_map_kf, voxel_m, p, &st);
  if (dynamic.empty()) return st;
  for (size_t k = 0; k < mapper.keyframes().size() && k < T_map_kf.size(); ++k) {
    const Eigen::Isometry3f T = T_map_kf[k].cast<float>();
    st.removed_points += mapper.erasePoints(k, [&](const Eigen::Vector3f& q) { return dynamic.count(voxelOf(T * q, voxel_m)) > 0; });
  }
  return st;
}

}  // namespace roadslam::mapping

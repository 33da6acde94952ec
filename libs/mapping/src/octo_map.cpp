#include "roadslam/mapping/octo_map.h"

#include <octomap/OcTree.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "ini_keys.h"

namespace roadslam::mapping {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

uint64_t pack(const octomap::OcTreeKey& k) {
  return static_cast<uint64_t>(k[0]) | (static_cast<uint64_t>(k[1]) << 16) | (static_cast<uint64_t>(k[2]) << 32);
}
octomap::OcTreeKey unpack(uint64_t v) {
  return octomap::OcTreeKey(v & 0xffff, (v >> 16) & 0xffff, (v >> 32) & 0xffff);
}
void sortUnique(std::vector<uint64_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

void OctoMapParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  enabled = readBool(cfg, s, "enabled", enabled);
  resolution_m = readDouble(cfg, s, "resolution_m", resolution_m);
  max_range_m = readDouble(cfg, s, "max_range_m", max_range_m);
  free_max_range_m = readDouble(cfg, s, "free_max_range_m", free_max_range_m);
  prob_hit = readDouble(cfg, s, "prob_hit", prob_hit);
  prob_miss = readDouble(cfg, s, "prob_miss", prob_miss);
  clamp_min = readDouble(cfg, s, "clamp_min", clamp_min);
  clamp_max = readDouble(cfg, s, "clamp_max", clamp_max);
  write_ot = readBool(cfg, s, "write_ot", write_ot);
  keyframe_spacing_m = readDouble(cfg, s, "keyframe_spacing_m", keyframe_spacing_m);
  rejectUnknownKeys(cfg, s, {"enabled", "resolution_m", "max_range_m", "free_max_range_m", "prob_hit", "prob_miss", "clamp_min", "clamp_max", "write_ot", "keyframe_spacing_m"});
  if (resolution_m <= 0 || max_range_m <= 0 || free_max_range_m < 0 || prob_hit <= 0.5 || prob_hit >= 1 ||
      prob_miss <= 0 || prob_miss >= 0.5 || clamp_min <= 0 || clamp_max >= 1 || clamp_min >= clamp_max) {
    throw std::runtime_error("[" + s + "]: need resolution_m, max_range_m > 0, 0.5 < prob_hit < 1, "
                             "0 < prob_miss < 0.5, 0 < clamp_min < clamp_max < 1");
  }
}

void OctoMapParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  cfg.write(s, "enabled", enabled);
  cfg.write(s, "resolution_m", resolution_m);
  cfg.write(s, "max_range_m", max_range_m);
  cfg.write(s, "free_max_range_m", free_max_range_m);
  cfg.write(s, "prob_hit", prob_hit);
  cfg.write(s, "prob_miss", prob_miss);
  cfg.write(s, "clamp_min", clamp_min);
  cfg.write(s, "clamp_max", clamp_max);
  cfg.write(s, "write_ot", write_ot);
  cfg.write(s, "keyframe_spacing_m", keyframe_spacing_m);
}

OctoMapBuilder::OctoMapBuilder(OctoMapParams params) : p_(params) { clear(); }
OctoMapBuilder::~OctoMapBuilder() = default;
OctoMapBuilder::OctoMapBuilder(OctoMapBuilder&&) noexcept = default;
OctoMapBuilder& OctoMapBuilder::operator=(OctoMapBuilder&&) noexcept = default;

void OctoMapBuilder::clear() {
  tree_ = std::make_unique<octomap::OcTree>(p_.resolution_m);
  tree_->setProbHit(p_.prob_hit);
  tree_->setProbMiss(p_.prob_miss);
  tree_->setClampingThresMin(p_.clamp_min);
  tree_->setClampingThresMax(p_.clamp_max);
}

const octomap::OcTree& OctoMapBuilder::tree() const { return *tree_; }
size_t OctoMapBuilder::numLeafs() const { return tree_->getNumLeafNodes(); }

InsertStats OctoMapBuilder::insert(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar) {
  const auto t0 = Clock::now();
  InsertStats st;
  const Eigen::Vector3d o = T_map_lidar.translation();
  const octomap::point3d origin(o.x(), o.y(), o.z());
  const double max_r2 = p_.max_range_m * p_.max_range_m;
  std::vector<uint64_t> occ, far;  // end voxels within max range; beyond it: voxels at max range
  occ.reserve(points_lidar.size());
  octomap::OcTreeKey key;
  for (const auto& q : points_lidar) {
    Eigen::Vector3d p = T_map_lidar * q.cast<double>();
    if (!p.allFinite()) continue;
    const bool beyond = (p - o).squaredNorm() > max_r2;
    // beyond max range: free space up to max range, no hit (octomap's insertPointCloud with maxrange)
    if (beyond) p = o + (p - o) * (p_.max_range_m / (p - o).norm());
    if (!tree_->coordToKeyChecked(octomap::point3d(p.x(), p.y(), p.z()), key)) continue;
    (beyond ? far : occ).push_back(pack(key));
    ++st.points;
  }
  sortUnique(occ);
  sortUnique(far);
  // one ray per distinct end voxel (to its centre), clipped to free_max_range_m
  std::vector<uint64_t> free;
  octomap::KeyRay ray;
  std::vector<uint64_t> ends = occ;
  ends.insert(ends.end(), far.begin(), far.end());
  for (uint64_t k : ends) {
    octomap::point3d end = tree_->keyToCoord(unpack(k));
    const octomap::point3d dir = end - origin;
    const double len = dir.norm();
    if (len > p_.free_max_range_m) end = origin + dir * static_cast<float>(p_.free_max_range_m / len);
    if (!tree_->computeRayKeys(origin, end, ray)) continue;
    for (const auto& rk : ray) free.push_back(pack(rk));
  }
  sortUnique(free);
  // a voxel with an end point in this scan is not freed by it (octomap computeUpdate)
  std::vector<uint64_t> free_only;
  free_only.reserve(free.size());
  std::set_difference(free.begin(), free.end(), occ.begin(), occ.end(), std::back_inserter(free_only));
  for (uint64_t k : free_only) tree_->updateNode(unpack(k), false, true);
  for (uint64_t k : occ) tree_->updateNode(unpack(k), true, true);
  tree_->updateInnerOccupancy();
  st.occupied_keys = occ.size();
  st.free_keys = free_only.size();
  st.ms = msSince(t0);
  return st;
}

InsertStats OctoMapBuilder::insertReference(const std::vector<Eigen::Vector3f>& points_lidar,
                                            const Eigen::Isometry3d& T_map_lidar) {
  const auto t0 = Clock::now();
  InsertStats st;
  octomap::Pointcloud cloud;
  for (const auto& q : points_lidar) {
    const Eigen::Vector3d p = T_map_lidar * q.cast<double>();
    if (!p.allFinite()) continue;
    cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  st.points = cloud.size();
  const Eigen::Vector3d o = T_map_lidar.translation();
  tree_->insertPointCloud(cloud, octomap::point3d(o.x(), o.y(), o.z()), p_.max_range_m);
  st.ms = msSince(t0);
  return st;
}

void OctoMapBuilder::writeBt(const std::string& path) const {
  const std::string tmp = tempPathFor(path);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f || !tree_->writeBinaryConst(f) || !f.flush()) {
      throw std::runtime_error("cannot write octomap '" + path + "'");
    }
  }
  commitTempFile(tmp, path);
}

void OctoMapBuilder::writeOt(const std::string& path) const {
  const std::string tmp = tempPathFor(path);
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f || !tree_->write(f) || !f.flush()) throw std::runtime_error("cannot write octomap '" + path + "'");
  }
  commitTempFile(tmp, path);
}

Agreement compareOctoMaps(const octomap::OcTree& reference, const octomap::OcTree& other) {
  Agreement a;
  size_t occ_same = 0, free_same = 0;
  for (auto it = reference.begin_leafs(), end = reference.end_leafs(); it != end; ++it) {
    const bool occ = reference.isNodeOccupied(*it);
    (occ ? a.ref_occupied : a.ref_free)++;
    const octomap::OcTreeNode* n = other.search(it.getCoordinate());
    if (n && other.isNodeOccupied(n) == occ) (occ ? occ_same : free_same)++;
  }
  a.occupied_percent = a.ref_occupied ? 100.0 * occ_same / a.ref_occupied : 0;
  a.free_percent = a.ref_free ? 100.0 * free_same / a.ref_free : 0;
  return a;
}

}  // namespace roadslam::mapping

#include "roadslam/mapping/octo_map.h"

#include <cerrno>
#include <octomap/OcTree.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "ini_keys.h"
#include "octo_grid.h"

namespace roadslam::mapping {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// The scan's end points in the map frame, as octomap receives them (float point3d).
std::vector<octomap::point3d> toMap(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar) {
  std::vector<octomap::point3d> out;
  out.reserve(points_lidar.size());
  for (const auto& q : points_lidar) {
    const Eigen::Vector3d p = T_map_lidar * q.cast<double>();
    if (!p.allFinite()) continue;
    out.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  return out;
}

octomap::point3d toPoint(const Eigen::Vector3d& v) {
  return octomap::point3d(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
}

}  // namespace

void OctoMapParams::fields(ParamTable& t) {
  t.flag("enabled", enabled);
  t.num("resolution_m", resolution_m);
  t.num("max_range_m", max_range_m);
  t.num("free_max_range_m", free_max_range_m);
  t.num("prob_hit", prob_hit);
  t.num("prob_miss", prob_miss);
  t.num("clamp_min", clamp_min);
  t.num("clamp_max", clamp_max);
  t.flag("write_ot", write_ot);
  t.num("keyframe_spacing_m", keyframe_spacing_m);
}

void OctoMapParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<OctoMapParams>());
  if (resolution_m <= 0 || max_range_m <= 0 || free_max_range_m < 0 || prob_hit <= 0.5 || prob_hit >= 1 ||
      prob_miss <= 0 || prob_miss >= 0.5 || clamp_min <= 0 || clamp_max >= 1 || clamp_min >= clamp_max) {
    throw std::runtime_error("[" + s + "]: need resolution_m, max_range_m > 0, 0.5 < prob_hit < 1, "
                             "0 < prob_miss < 0.5, 0 < clamp_min < clamp_max < 1");
  }
}

void OctoMapParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

OctoMapBuilder::OctoMapBuilder(OctoMapParams params) : p_(params) { clear(); }
OctoMapBuilder::~OctoMapBuilder() = default;
OctoMapBuilder::OctoMapBuilder(OctoMapBuilder&&) noexcept = default;
OctoMapBuilder& OctoMapBuilder::operator=(OctoMapBuilder&&) noexcept = default;

std::unique_ptr<octomap::OcTree> OctoMapBuilder::newTree() const {
  auto t = std::make_unique<octomap::OcTree>(p_.resolution_m);
  t->setProbHit(p_.prob_hit);
  t->setProbMiss(p_.prob_miss);
  t->setClampingThresMin(p_.clamp_min);
  t->setClampingThresMax(p_.clamp_max);
  return t;
}

void OctoMapBuilder::clear() {
  tree_ = newTree();
  // the grid uses the tree's own float log-odds so that both give the same values
  detail::LogOddsModel m;
  m.hit = tree_->getProbHitLog();
  m.miss = tree_->getProbMissLog();
  m.min = tree_->getClampingThresMinLog();
  m.max = tree_->getClampingThresMaxLog();
  if (grid_) {
    grid_->clear();
  } else {
    grid_ = std::make_unique<detail::VoxelGrid>(m);
  }
  tree_current_ = grid_current_ = true;
}

void OctoMapBuilder::materialiseTree() const {
  if (tree_current_) return;
  tree_ = newTree();
  // setNodeValue per leaf without inner updates, then one bottom-up pass; pruning merges only
  // children with equal log-odds (lossless), as octomap's non-lazy insertion does on the way
  grid_->forEachKnown([&](const octomap::OcTreeKey& k, float lo) { tree_->setNodeValue(k, lo, true); });
  tree_->updateInnerOccupancy();
  tree_->prune();
  tree_current_ = true;
}

void OctoMapBuilder::importTree() {
  if (grid_current_) return;
  grid_->clear();
  const unsigned depth = tree_->getTreeDepth();
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    const octomap::OcTreeKey k0 = it.getIndexKey();  // lowest corner of a pruned leaf
    const unsigned n = 1u << (depth - it.getDepth());
    const float lo = it->getLogOdds();
    for (unsigned x = 0; x < n; ++x)
      for (unsigned y = 0; y < n; ++y)
        for (unsigned z = 0; z < n; ++z)
          grid_->set(octomap::OcTreeKey(k0[0] + x, k0[1] + y, k0[2] + z), lo);
  }
  grid_current_ = true;
}

const octomap::OcTree& OctoMapBuilder::tree() const {
  materialiseTree();
  return *tree_;
}
size_t OctoMapBuilder::numLeafs() const { return tree().getNumLeafNodes(); }
size_t OctoMapBuilder::gridBytes() const { return grid_->memoryBytes(); }
size_t OctoMapBuilder::numVoxels() const {
  if (grid_current_) return grid_->numKnown();
  size_t n = 0;  // after insertReference(): the tree's leaves, pruned ones counted per voxel
  for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it) {
    n += size_t{1} << (3 * (tree_->getTreeDepth() - it.getDepth()));
  }
  return n;
}

InsertStats OctoMapBuilder::insert(const std::vector<Eigen::Vector3f>& points_lidar, const Eigen::Isometry3d& T_map_lidar) {
  const auto t0 = Clock::now();
  importTree();
  InsertStats st;
  const std::vector<octomap::point3d> pts = toMap(points_lidar, T_map_lidar);
  st.points = pts.size();  // as insertReference(): beyond max range they still clear free space
  const octomap::point3d origin = toPoint(T_map_lidar.translation());
  const double factor = 1.0 / p_.resolution_m;
  detail::ScanUpdate g(*grid_);
  // hits first: a voxel holding an end point is never freed by the same scan (computeUpdate)
  octomap::OcTreeKey key;
  for (const auto& p : pts) {
    if ((p - origin).norm() > p_.max_range_m) continue;
    if (detail::coordToKey(p, factor, key) && g.hit(key)) ++st.occupied_keys;
  }
  // then one ray per end point (as OccupancyOcTreeBase::computeUpdate), ending at the point,
  // or at free_max_range_m / max_range_m along it; the touched bit keeps one update per voxel
  size_t cells = 0, freed = 0;  // locals, not st's fields: kept in registers in the hot loop
  const auto visit = [&](const octomap::OcTreeKey& k) {
    ++cells;
    freed += g.miss(k);
  };
  for (const auto& p : pts) {
    const double range = (p - origin).norm();
    const double clip = range > p_.max_range_m ? p_.max_range_m : p_.free_max_range_m;
    if (range <= clip) {
      detail::castRay(origin, p, p_.resolution_m, visit);
    } else {
      const octomap::point3d end = origin + (p - origin).normalized() * static_cast<float>(std::min(clip, p_.free_max_range_m));
      detail::castRay(origin, end, p_.resolution_m, visit);
    }
  }
  st.ray_cells = cells;
  st.free_keys = freed;
  tree_current_ = false;
  st.ms = msSince(t0);
  return st;
}

InsertStats OctoMapBuilder::insertReference(const std::vector<Eigen::Vector3f>& points_lidar,
                                            const Eigen::Isometry3d& T_map_lidar) {
  const auto t0 = Clock::now();
  materialiseTree();
  InsertStats st;
  octomap::Pointcloud cloud;
  for (const auto& p : toMap(points_lidar, T_map_lidar)) cloud.push_back(p);
  st.points = cloud.size();
  tree_->insertPointCloud(cloud, toPoint(T_map_lidar.translation()), p_.max_range_m);
  grid_current_ = false;
  st.ms = msSince(t0);
  return st;
}

void OctoMapBuilder::writeBt(const std::string& path) const {
  TempFile tmp(path);
  {
    std::ofstream f(tmp.path(), std::ios::binary | std::ios::trunc);
    errno = 0;
    // octomap's writeBinaryConst() with its header, without the " done." it prints on stderr
    // (AbstractOccupancyOcTree.cpp, OCTOMAP_DEBUG in Debian's library build): a --quiet run stays quiet.
    const auto& t = tree();
    f << "# Octomap OcTree binary file\n# (feel free to add / change comments, but leave the first line as it is!)\n#\n"
      << "id " << t.getTreeType() << "\nsize " << t.size() << "\nres " << t.getResolution() << "\ndata\n";
    if (!f || !t.writeBinaryData(f) || !f.flush()) throw std::runtime_error(tmp.failure("octomap"));
  }
  tmp.commit();
}

void OctoMapBuilder::writeOt(const std::string& path) const {
  TempFile tmp(path);
  {
    std::ofstream f(tmp.path(), std::ios::binary | std::ios::trunc);
    errno = 0;
    if (!f || !tree().write(f) || !f.flush()) throw std::runtime_error(tmp.failure("octomap"));
  }
  tmp.commit();
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
  for (auto it = other.begin_leafs(), end = other.end_leafs(); it != end; ++it) {
    if (!reference.search(it.getCoordinate())) ++a.other_unknown;
  }
  a.occupied_percent = a.ref_occupied ? 100.0 * occ_same / a.ref_occupied : 0;
  a.free_percent = a.ref_free ? 100.0 * free_same / a.ref_free : 0;
  return a;
}

}  // namespace roadslam::mapping

#pragma once
/// \file octo_grid.h
/// Private to libs/mapping: the flat voxel grid that holds OctoMapBuilder's occupancy between
/// keyframes. Voxels are octomap leaves (OcTreeKey at depth 16, so keys and coordinates are
/// octomap's own), grouped in 8x8x8 blocks found through an open-addressing hash of the block
/// coordinates. A voxel keeps octomap's float log-odds; a block keeps a known mask and a
/// "touched in this scan" mask, so a scan updates each voxel once (octomap's KeySet semantics,
/// OccupancyOcTreeBase::computeUpdate) in O(1) per ray cell: no sort, no per-cell set, no tree
/// descent (the tree is materialised from the grid only when it is read).

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

// OcTreeKey.h uses uint16_t and size_t without including their headers
#include <octomap/OcTreeKey.h>
#include <octomap/octomap_types.h>

namespace roadslam::mapping::detail {

struct VoxelBlock {
  static constexpr unsigned kBits = 3;                      ///< 8 voxels per side
  static constexpr unsigned kSide = 1u << kBits;
  static constexpr unsigned kVoxels = kSide * kSide * kSide;
  static constexpr unsigned kWords = kVoxels / 64;
  float log_odds[kVoxels];   ///< octomap log-odds of each voxel (0 while unknown) [-]
  uint64_t known[kWords];    ///< voxel ever updated
  uint64_t touched[kWords];  ///< voxel updated in scan `scan`
  uint32_t scan;
};

/// Log-odds sensor model as octomap stores it (AbstractOccupancyOcTree: floats from logodds(p)).
struct LogOddsModel {
  float hit = 0, miss = 0, min = 0, max = 0;  ///< [-]
};

class VoxelGrid {
 public:
  explicit VoxelGrid(LogOddsModel model);

  void clear();
  /// Starts a scan: every voxel may be updated once again (blockOf() clears the touched masks).
  void beginScan() { ++scan_; }

  /// Sets voxel \p k to \p log_odds (known), outside any scan bookkeeping.
  void set(const octomap::OcTreeKey& k, float log_odds);

  /// Calls \p fn(key, log_odds) for every known voxel, block by block.
  void forEachKnown(const std::function<void(const octomap::OcTreeKey&, float)>& fn) const;

  size_t numKnown() const { return known_; }
  size_t numBlocks() const { return block_keys_.size(); }
  size_t memoryBytes() const;  ///< blocks and hash table [bytes]
  const LogOddsModel& model() const { return model_; }

  static uint64_t blockKey(const octomap::OcTreeKey& k) {
    constexpr unsigned s = VoxelBlock::kBits, w = 16 - VoxelBlock::kBits;
    return static_cast<uint64_t>(k[0] >> s) | (static_cast<uint64_t>(k[1] >> s) << w) |
           (static_cast<uint64_t>(k[2] >> s) << (2 * w));
  }
  static unsigned voxelIndex(const octomap::OcTreeKey& k) {
    constexpr unsigned m = VoxelBlock::kSide - 1, s = VoxelBlock::kBits;
    return (k[0] & m) | ((k[1] & m) << s) | ((k[2] & m) << (2 * s));
  }
  /// The block with key \p bk, created when new; its touched mask belongs to the current scan.
  /// The reference stays valid until the next blockOf().
  VoxelBlock& blockOf(uint64_t bk);
  void addKnown(size_t n) { known_ += n; }

 private:
  static constexpr unsigned kPageBits = 6;  ///< 64 blocks per page: blocks never move
  struct Slot {
    uint64_t key;    ///< block key, or ~0 when empty
    uint32_t block;  ///< index of the block
  };
  VoxelBlock& block(size_t i) { return pages_[i >> kPageBits][i & ((1u << kPageBits) - 1)]; }
  const VoxelBlock& block(size_t i) const { return pages_[i >> kPageBits][i & ((1u << kPageBits) - 1)]; }
  void grow();

  LogOddsModel model_;
  std::vector<std::unique_ptr<VoxelBlock[]>> pages_;
  std::vector<uint64_t> block_keys_;  ///< key of block i [-]
  std::vector<Slot> slots_;           ///< open addressing, linear probing, load <= 1/2
  uint32_t scan_ = 0;
  size_t known_ = 0;
};

/// One scan's updates. Lives on the caller's stack, so its block cache and sensor model stay in
/// registers across the ray loop (the grid's members would be reloaded after every store).
class ScanUpdate {
 public:
  explicit ScanUpdate(VoxelGrid& g) : grid_(g), model_(g.model()) { g.beginScan(); }
  ~ScanUpdate() { grid_.addKnown(new_known_); }
  ScanUpdate(const ScanUpdate&) = delete;
  ScanUpdate& operator=(const ScanUpdate&) = delete;

  bool hit(const octomap::OcTreeKey& k) { return update(k, model_.hit); }
  bool miss(const octomap::OcTreeKey& k) { return update(k, model_.miss); }

  /// Adds \p delta to voxel \p k, then clamps (OccupancyOcTreeBase::updateNodeLogOdds), unless
  /// it was already updated in this scan. Returns true when it was updated.
  bool update(const octomap::OcTreeKey& k, float delta) {
    const uint64_t bk = VoxelGrid::blockKey(k);
    if (bk != key_) {  // consecutive ray cells mostly share a block
      block_ = &grid_.blockOf(bk);
      key_ = bk;
    }
    VoxelBlock& b = *block_;
    const unsigned i = VoxelGrid::voxelIndex(k), w = i >> 6;
    const uint64_t bit = uint64_t{1} << (i & 63);
    if (b.touched[w] & bit) return false;
    b.touched[w] |= bit;
    float v = b.log_odds[i];
    if (!(b.known[w] & bit)) {  // a new octomap node starts at log-odds 0
      b.known[w] |= bit;
      v = 0;
      ++new_known_;
    }
    v += delta;
    if (v < model_.min) v = model_.min;
    else if (v > model_.max) v = model_.max;
    b.log_odds[i] = v;
    return true;
  }

 private:
  VoxelGrid& grid_;
  const LogOddsModel model_;
  uint64_t key_ = ~uint64_t{0};
  VoxelBlock* block_ = nullptr;
  size_t new_known_ = 0;
};

/// Calls \p visit(key) for every cell OcTreeBaseImpl::computeRayKeys(origin, end) returns, in
/// the same order and with the same float/double arithmetic (Amanatides & Woo 1987 DDA), so the
/// free cells equal octomap's; \p resolution_m as the tree's. Returns false where octomap does
/// (a coordinate outside the tree).
template <typename Visit>
bool castRay(const octomap::point3d& origin, const octomap::point3d& end, double resolution_m, Visit&& visit);

/// octomap's coordToKeyChecked for one coordinate at depth 16.
inline bool coordToKey(double coordinate, double resolution_factor, uint16_t& key) {
  constexpr int kMax = 32768;  // OcTreeBaseImpl::tree_max_val at depth 16
  const int scaled = static_cast<int>(std::floor(resolution_factor * coordinate)) + kMax;
  if (scaled < 0 || scaled >= 2 * kMax) return false;
  key = static_cast<uint16_t>(scaled);
  return true;
}
inline bool coordToKey(const octomap::point3d& p, double resolution_factor, octomap::OcTreeKey& key) {
  return coordToKey(p(0), resolution_factor, key[0]) && coordToKey(p(1), resolution_factor, key[1]) &&
         coordToKey(p(2), resolution_factor, key[2]);
}

template <typename Visit>
bool castRay(const octomap::point3d& origin, const octomap::point3d& end, double resolution_m, Visit&& visit) {
  const double factor = 1.0 / resolution_m;
  octomap::OcTreeKey key_origin, key_end;
  if (!coordToKey(origin, factor, key_origin) || !coordToKey(end, factor, key_end)) return false;
  if (key_origin == key_end) return true;
  visit(key_origin);
  octomap::point3d direction = end - origin;
  const float length = static_cast<float>(direction.norm());
  direction /= length;
  int step[3];
  double t_max[3], t_delta[3];
  octomap::OcTreeKey current = key_origin;
  for (unsigned i = 0; i < 3; ++i) {
    step[i] = direction(i) > 0.0 ? 1 : (direction(i) < 0.0 ? -1 : 0);
    if (step[i] != 0) {
      // voxel border in the ray's direction (OcTreeBaseImpl::keyToCoord + half a voxel)
      double border = (double(int(current[i]) - 32768) + 0.5) * resolution_m;
      border += static_cast<float>(step[i] * resolution_m * 0.5);
      t_max[i] = (border - origin(i)) / direction(i);
      t_delta[i] = resolution_m / std::fabs(direction(i));
    } else {
      t_max[i] = t_delta[i] = std::numeric_limits<double>::max();
    }
  }
  // the same steps as octomap's loop, with the state in scalars (no indexed stack arrays)
  double tx = t_max[0], ty = t_max[1], tz = t_max[2];
  uint16_t cx = current[0], cy = current[1], cz = current[2];
  const auto sx = static_cast<uint16_t>(step[0]), sy = static_cast<uint16_t>(step[1]),
             sz = static_cast<uint16_t>(step[2]);  // added modulo 2^16 as octomap's key_type
  for (;;) {
    if (tx < ty) {
      if (tx < tz) {
        cx = static_cast<uint16_t>(cx + sx);
        tx += t_delta[0];
      } else {
        cz = static_cast<uint16_t>(cz + sz);
        tz += t_delta[2];
      }
    } else if (ty < tz) {
      cy = static_cast<uint16_t>(cy + sy);
      ty += t_delta[1];
    } else {
      cz = static_cast<uint16_t>(cz + sz);
      tz += t_delta[2];
    }
    if (cx == key_end[0] && cy == key_end[1] && cz == key_end[2]) break;
    // past the end point: discretisation error missed key_end (octomap stops here too)
    if (std::min(std::min(tx, ty), tz) > length) break;
    visit(octomap::OcTreeKey(cx, cy, cz));
  }
  return true;
}

}  // namespace roadslam::mapping::detail

#pragma once
// Private: the NDT grid behind roadslam::registration::Target (Magnusson 2009, Ch. 6).
// One open-addressing hash from packed voxel key to a dense cell index, cell statistics gathered
// in one pass without per-cell point lists, coarse levels summed from the finest level's sums.

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <vector>

namespace roadslam::registration {

/// Integer voxel coordinates packed into 63 bits (21 bits per axis, +-1M cells).
inline uint64_t voxelKey(int64_t x, int64_t y, int64_t z) {
  const auto c = [](int64_t v) { return static_cast<uint64_t>(v + (1 << 20)) & 0x1FFFFFu; };
  return (c(x) << 42) | (c(y) << 21) | c(z);
}
inline uint64_t voxelKey(const Eigen::Vector3d& p, double inv_size) {
  return voxelKey(static_cast<int64_t>(std::floor(p.x() * inv_size)), static_cast<int64_t>(std::floor(p.y() * inv_size)),
                  static_cast<int64_t>(std::floor(p.z() * inv_size)));
}
/// Key of the voxel twice as large that contains voxel \p key: floor(c / 2) per axis, which equals
/// floor(x / (2 res)) exactly since halving 1/res is exact in floating point.
inline uint64_t parentKey(uint64_t key) {
  const auto f = [](uint64_t field) { return (static_cast<int64_t>(field) - (1 << 20)) >> 1; };
  return voxelKey(f(key >> 42), f((key >> 21) & 0x1FFFFFu), f(key & 0x1FFFFFu));
}

/// Open-addressing (linear probing) map from a packed voxel key to a dense index 0..size()-1,
/// Fibonacci hashing; load factor <= 1/2. A probe touches one 16-byte slot in the common case,
/// where std::unordered_map chases a node pointer.
class FlatIndex {
 public:
  static constexpr uint64_t kEmpty = ~uint64_t{0};  // voxel keys use 63 bits: never equal
  explicit FlatIndex(size_t expected = 16) { rehash(expected * 2); }

  /// Index of \p key, inserting size() when absent (\p inserted tells).
  int32_t findOrInsert(uint64_t key, bool& inserted) {
    if (2 * (size_ + 1) > slots_.size()) rehash(slots_.size() * 2);
    size_t i = slot(key);
    while (slots_[i].key != kEmpty) {
      if (slots_[i].key == key) {
        inserted = false;
        return slots_[i].value;
      }
      i = (i + 1) & mask_;
    }
    inserted = true;
    slots_[i] = {key, static_cast<int32_t>(size_)};
    return static_cast<int32_t>(size_++);
  }
  /// Index of \p key or -1.
  int32_t find(uint64_t key) const {
    for (size_t i = slot(key);; i = (i + 1) & mask_) {
      if (slots_[i].key == key) return slots_[i].value;
      if (slots_[i].key == kEmpty) return -1;
    }
  }
  size_t size() const { return size_; }

 private:
  struct Slot {
    uint64_t key = kEmpty;
    int32_t value = -1;
  };
  size_t slot(uint64_t key) const { return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_); }
  void rehash(size_t min_slots);

  std::vector<Slot> slots_;
  size_t mask_ = 0, size_ = 0;
  int shift_ = 64;
};

/// One NDT cell: the Gaussian of the target points inside it (Magnusson 2009, eq. 6.2-6.3).
struct NdtCell {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();      ///< [m], target frame
  Eigen::Matrix3d cov_inv = Eigen::Matrix3d::Zero();   ///< regularised inverse covariance [1/m^2]
  bool valid = false;  ///< enough points and a positive covariance; invalid cells are skipped
};

/// One resolution level. index maps every occupied voxel (valid or not) to cells[i] / normals[i].
struct NdtGrid {
  double resolution_m = 1;
  FlatIndex index;
  std::vector<NdtCell> cells;
  size_t num_valid = 0;                  ///< cells with valid = true [-]
  std::vector<Eigen::Vector3d> normals;  ///< eigenvector of the smallest eigenvalue (degeneracy analysis)
  /// Finest level only: target point indices grouped by cell, cell i owns
  /// bucket_points[bucket_begin[i] .. bucket_begin[i+1]) (nearest-point search without a kd-tree).
  std::vector<uint32_t> bucket_begin, bucket_points;
};

/// Builds \p levels grids, coarse to fine (finest = \p res_m, each coarser one twice the size),
/// with point buckets on the finest. Cells with fewer than max(min_pts, 4) points are invalid.
std::vector<NdtGrid> buildNdtGrids(const std::vector<Eigen::Vector3d>& points, double res_m, int levels, int min_pts);

/// Nearest of \p points to \p x among the 27 finest cells around x, within \p max_dist2 [m^2]
/// (exact for distances up to the cell size); returns the point index or -1, d2 its squared distance.
int nearestInGrid(const NdtGrid& finest, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& x,
                  double max_dist2, double& d2);

}  // namespace roadslam::registration

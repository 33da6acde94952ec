#pragma once
/// \file voxel_hash.h
/// Hash of an integer voxel key, for the voxel maps and grids across the libraries.
#include <Eigen/Core>
#include <cstddef>

namespace roadslam {

/// Teschner et al. 2003, "Optimized Spatial Hashing for Collision Detection of Deformable Objects"
/// (the hash KISS-ICP uses): XOR of the coordinates times three large primes.
struct VoxelKeyHash {
  std::size_t operator()(const Eigen::Vector3i& k) const noexcept {
    return static_cast<std::size_t>(k.x()) * 73856093u ^ static_cast<std::size_t>(k.y()) * 19349669u ^
           static_cast<std::size_t>(k.z()) * 83492791u;
  }
};

}  // namespace roadslam

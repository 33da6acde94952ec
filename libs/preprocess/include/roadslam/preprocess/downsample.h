#pragma once
/// \file downsample.h
/// Point-count reduction: random subsampling to a fraction, voxel grid, statistical outlier removal.

#include "roadslam/common/scan.h"

#include <cstdint>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::preprocess {

/// Keeps exactly round(keep_fraction * n) points chosen uniformly at random, in their original order
/// (selection sampling, Knuth TAOCP vol. 2, 3.4.2 Algorithm S). Deterministic for a seed.
struct RandomDownsampleParams {
  double keep_fraction = 0.5;  ///< fraction of points kept, (0, 1] [-]; ini `random_keep_fraction`, thesis `downS`
  uint64_t seed = 1;           ///< random seed [-]; ini `random_seed` (advanced per frame by the chain)
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};
size_t randomDownsample(std::vector<ScanPoint>& pts, const RandomDownsampleParams& p);

/// One point per occupied cubic voxel: the centroid of its points (x, y, z, intensity averaged; time,
/// ring and return index of the first) or the first point that fell in it. Output in the order the
/// voxels were first hit. Hash grid with open addressing: O(n), no sort. Non-finite points and
/// points more than 2^20 voxels from the origin are dropped (counted in the return value).
struct VoxelParams {
  enum class Mode { Centroid, First };
  double voxel_size_m = 0.25;  ///< voxel edge [m]; ini `voxel_size_m`
  Mode mode = Mode::Centroid; ///< ini `voxel_mode` = centroid | first
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};
size_t voxelDownsample(std::vector<ScanPoint>& pts, const VoxelParams& p);

/// Integer voxel coordinates of a point: floor(coord / voxel_size) per axis (exposed for tests).
struct VoxelKey {
  int32_t ix, iy, iz;
};
VoxelKey voxelOf(const ScanPoint& pt, double voxel_size_m);

/// Statistical outlier removal (Rusu et al. 2008, PCL's StatisticalOutlierRemoval): for each point
/// the mean distance to its k nearest neighbours; points whose mean exceeds mu + std_mul * sigma of
/// all means are removed. k-d tree by nanoflann.
struct SorParams {
  int k = 10;            ///< neighbours [-]; ini `sor_k`
  double std_mul = 2.0;  ///< threshold in standard deviations [-]; ini `sor_std_mul`
  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};
size_t removeStatisticalOutliers(std::vector<ScanPoint>& pts, const SorParams& p);

}  // namespace roadslam::preprocess

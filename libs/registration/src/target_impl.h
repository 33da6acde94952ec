#pragma once
// Private: search structures behind roadslam::registration::Target.

#include "roadslam/registration/registration.h"
#include "ndt_grid.h"

#include <nanoflann.hpp>

#include <cstdint>
#include <vector>

namespace roadslam::registration {

/// nanoflann dataset adaptor over a PointCloud.
struct CloudAdaptor {
  const PointCloud* pts = nullptr;
  size_t kdtree_get_point_count() const { return pts->size(); }
  double kdtree_get_pt(size_t i, size_t dim) const { return (*pts)[i][static_cast<Eigen::Index>(dim)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>,
                                                   CloudAdaptor, 3, uint32_t>;

struct Target::Impl {
  Method method = Method::IcpPointToPlane;
  PointCloud points;   ///< finite target points [m]
  int normal_k = 10;   ///< neighbours of the covariance normal [-]
  /// Normals are computed on first use and cached: a scan-to-map alignment touches a fraction of
  /// the map, so computing all of them up front costs more than the alignment (measured 20 ms for a
  /// 17.7k-point map vs 7.6 ms of alignment).
  mutable PointCloud normals;               ///< unit normals; zero where undefined (< 3 neighbours)
  mutable std::vector<uint8_t> has_normal;  ///< 1 once normals[i] is computed
  const Eigen::Vector3d& normal(size_t i) const {
    if (!has_normal[i]) computeNormal(i);
    return normals[i];
  }
  void computeNormal(size_t i) const;
  size_t dropped = 0;
  CloudAdaptor adaptor;
  std::unique_ptr<KdTree> tree;  ///< ICP only: NDT finds nearest points through its finest grid's buckets
  std::vector<NdtGrid> ndt;      ///< NDT only: coarse to fine
};

/// Nearest target point within max_dist2 [m^2]; returns index or -1.
inline int nearest(const Target::Impl& t, const Eigen::Vector3d& x, double max_dist2, double& d2) {
  uint32_t idx = 0;
  nanoflann::KNNResultSet<double, uint32_t> rs(1);
  rs.init(&idx, &d2);
  t.tree->findNeighbors(rs, x.data(), nanoflann::SearchParams(10));
  if (rs.size() == 0 || d2 > max_dist2) return -1;
  return static_cast<int>(idx);
}

}  // namespace roadslam::registration

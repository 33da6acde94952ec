#pragma once
/// \file fpfh.h
/// Fast Point Feature Histograms (Rusu, Blodow & Beetz, "Fast Point Feature Histograms (FPFH) for 3D
/// registration", ICRA 2009): a 33-bin description of the surface around a point from the angles between
/// its normal and its neighbours' normals, invariant to the pose. Our own implementation over nanoflann,
/// binned like PCL / Open3D (3 x 11 bins of the Darboux-frame angles alpha, phi, theta, each group summing
/// to 100) so the descriptors compare with theirs.

#include <Eigen/Core>
#include <vector>

#include "roadslam/registration/point_cloud.h"

namespace roadslam::registration {

/// One FPFH descriptor: bins [0,11) the angle theta = atan2(w.n_t, u.n_t) (Rusu 2009 eq. 2, f1),
/// [11,22) alpha = v.n_t, [22,33) phi = u.(p_t-p_s)/|p_t-p_s| [-].
using Fpfh = Eigen::Matrix<float, 33, 1>;

/// Unit normals from the covariance of the neighbours within \p radius_m [m] (Hoppe et al. 1992),
/// oriented towards \p viewpoint (same frame as \p points, e.g. the lidar origin). A point with fewer
/// than \p min_neighbours neighbours gets a zero normal [-].
PointCloud estimateNormals(const PointCloud& points, double radius_m, const Eigen::Vector3d& viewpoint,
                           int min_neighbours = 5);

/// FPFH of the points \p at (indices into \p points) from the neighbours within \p radius_m [m] over all
/// of \p points, whose \p normals (estimateNormals) may be zero (such points are skipped as neighbours).
/// At most \p max_neighbours nearest neighbours enter a histogram (0: all).
std::vector<Fpfh> computeFpfh(const PointCloud& points, const PointCloud& normals, const std::vector<int>& at,
                              double radius_m, int max_neighbours = 0);

}  // namespace roadslam::registration

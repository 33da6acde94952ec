#include "target_impl.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

namespace roadslam::registration {
// Normal = eigenvector of the smallest eigenvalue of the k-neighbourhood covariance (Hoppe et al. 1992).
void Target::Impl::computeNormal(size_t i) const {
  constexpr size_t kMaxK = 32;
  std::array<uint32_t, kMaxK> idx{};
  std::array<double, kMaxK> d2{};
  const size_t kk = std::min({static_cast<size_t>(std::max(normal_k, 3)), kMaxK, points.size()});
  has_normal[i] = 1;
  const size_t n = tree->knnSearch(points[i].data(), kk, idx.data(), d2.data());
  if (n < 3) return;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < n; ++j) mean += points[idx[j]];
  mean /= static_cast<double>(n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (size_t j = 0; j < n; ++j) {
    const Eigen::Vector3d d = points[idx[j]] - mean;
    cov.noalias() += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  normals[i] = es.eigenvectors().col(0);
}

Target::Target(const PointCloud& points_target, const Params& params) : impl_(std::make_unique<Impl>()) {
  Impl& t = *impl_;
  t.method = params.method;
  t.points.reserve(points_target.size());
  for (const auto& p : points_target) {
    if (p.allFinite()) t.points.push_back(p);
    else ++t.dropped;
  }
  if (params.method == Method::Ndt) {
    // No kd-tree: the finest grid's point buckets serve the final nearest-point statistics (a kd-tree
    // build cost more than the whole alignment in scan-to-map odometry).
    t.ndt = buildNdtGrids(t.points, params.ndt_resolution_m, params.ndt_levels, params.ndt_min_points_per_cell);
  } else {
    t.adaptor.pts = &t.points;
    t.tree = std::make_unique<KdTree>(3, t.adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
    t.normal_k = params.normal_neighbours;
    t.normals.assign(t.points.size(), Eigen::Vector3d::Zero());
    t.has_normal.assign(t.points.size(), 0);
  }
}

Target::~Target() = default;
Target::Target(Target&&) noexcept = default;
Target& Target::operator=(Target&&) noexcept = default;
size_t Target::size() const { return impl_->points.size(); }
size_t Target::numDroppedNonFinite() const { return impl_->dropped; }
Method Target::method() const { return impl_->method; }

}  // namespace roadslam::registration

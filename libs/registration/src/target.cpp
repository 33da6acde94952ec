#include "target_impl.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>

namespace roadslam::registration {
namespace {

NdtGrid buildNdtGrid(const PointCloud& pts, double res, int min_pts) {
  struct Acc {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
    int n = 0;
  };
  std::unordered_map<uint64_t, Acc, VoxelHash> acc;
  acc.reserve(pts.size() / 4 + 16);
  const double inv = 1.0 / res;
  for (const auto& p : pts) {
    Acc& a = acc[voxelKey(p, inv)];
    a.sum += p;
    a.sum_sq.noalias() += p * p.transpose();
    ++a.n;
  }
  NdtGrid g;
  g.resolution_m = res;
  g.cells.reserve(acc.size());
  for (const auto& [key, a] : acc) {
    if (a.n < std::max(min_pts, 4)) continue;
    const Eigen::Vector3d mean = a.sum / a.n;
    Eigen::Matrix3d cov = (a.sum_sq - a.n * mean * mean.transpose()) / (a.n - 1);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(cov);
    Eigen::Vector3d ev = es.eigenvalues();
    if (!(ev(2) > 0)) continue;
    // Inflate near-singular covariances (Magnusson 2009, Sec. 6.2: smallest eigenvalue >= 0.001
    // of the largest; PCL uses 0.01, which keeps the Hessian better conditioned).
    for (int i = 0; i < 2; ++i) ev(i) = std::max(ev(i), 0.01 * ev(2));
    NdtCell c;
    c.mean = mean;
    c.cov_inv = es.eigenvectors() * ev.cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
    c.normal = es.eigenvectors().col(0);
    g.index.emplace(key, static_cast<int>(g.cells.size()));
    g.cells.push_back(c);
  }
  return g;
}

}  // namespace

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
  t.adaptor.pts = &t.points;
  t.tree = std::make_unique<KdTree>(3, t.adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  if (params.method == Method::Ndt) {
    for (int l = std::max(params.ndt_levels, 1) - 1; l >= 0; --l) {
      t.ndt.push_back(buildNdtGrid(t.points, params.ndt_resolution_m * std::ldexp(1.0, l),
                                   params.ndt_min_points_per_cell));
    }
  } else {
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

#include "roadslam/odometry/gaussian_voxel_map.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace roadslam::odometry {
namespace {

constexpr int kMinPointsForCovariance = 5;
// GICP plane regularisation (Segal et al. 2009, Sec. III-B): eigenvalues (1, eps, eps) of the
// information, the 1 along the normal, so the Mahalanobis distance on a flat voxel is the
// point-to-plane distance in metres.
constexpr double kInPlaneInfo = 1e-2;

}  // namespace

GaussianVoxelMap::GaussianVoxelMap(double voxel_m, int max_points_per_voxel, double radius_m, int neighbours)
    : voxel_m_(voxel_m),
      inv_voxel_(1.0 / voxel_m),
      radius_m_(radius_m),
      max_points_(max_points_per_voxel),
      neighbours_(neighbours == 1 ? 1 : 7) {}

void GaussianVoxelMap::refresh(Voxel& v) const {
  v.mean = v.sum / v.n;
  v.valid = v.n >= kMinPointsForCovariance;
  if (!v.valid) return;
  const Eigen::Matrix3d cov = v.scatter / v.n - v.mean * v.mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  const Eigen::Matrix3d& V = es.eigenvectors();  // ascending eigenvalues: column 0 is the normal
  const Eigen::Vector3d d(1.0, kInPlaneInfo, kInPlaneInfo);
  v.info = V * d.asDiagonal() * V.transpose();
}

void GaussianVoxelMap::insert(const std::vector<Eigen::Vector3d>& points_map) {
  // pointers to unordered_map elements survive rehashing, so the touched list stays valid
  std::vector<Voxel*> touched;
  touched.reserve(points_map.size() / 4);
  ++batch_;
  for (const auto& p : points_map) {
    Voxel& v = voxels_[keyOf(p)];
    if (v.n >= max_points_) continue;
    if (v.batch != batch_) {
      v.batch = batch_;
      touched.push_back(&v);
    }
    v.sum += p;
    v.scatter.noalias() += p * p.transpose();
    ++v.n;
  }
  for (Voxel* v : touched) refresh(*v);
}

void GaussianVoxelMap::removeFar(const Eigen::Vector3d& origin_map) {
  const double r2 = radius_m_ * radius_m_;
  for (auto it = voxels_.begin(); it != voxels_.end();) {
    if ((it->second.mean - origin_map).squaredNorm() > r2) {
      it = voxels_.erase(it);
    } else {
      ++it;
    }
  }
}

std::vector<Eigen::Vector3d> GaussianVoxelMap::means() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(voxels_.size());
  for (const auto& [k, v] : voxels_) {
    if (v.valid) out.push_back(v.mean);
  }
  return out;
}

const GaussianVoxelMap::Voxel* GaussianVoxelMap::nearest(const Eigen::Vector3d& x, double max_dist_m) const {
  // The voxel holding x and its face neighbours (DIRECT7 of fast_gicp's VGICP, Koide et al. 2021):
  // a quarter of the hash look-ups of the full 27-neighbourhood for the same pairs in practice.
  static const int kOffsets[7][3] = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0},
                                     {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  const Eigen::Vector3i k = keyOf(x);
  const Voxel* best = nullptr;
  double best_d2 = max_dist_m * max_dist_m;
  for (int n = 0; n < neighbours_; ++n) {
    const auto it = voxels_.find(Eigen::Vector3i(k.x() + kOffsets[n][0], k.y() + kOffsets[n][1],
                                                 k.z() + kOffsets[n][2]));
    if (it == voxels_.end() || !it->second.valid) continue;
    const double d2 = (it->second.mean - x).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = &it->second;
    }
  }
  return best;
}

}  // namespace roadslam::odometry

#include "roadslam/odometry/vertical_structures.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <unordered_map>

#include "roadslam/common/voxel_hash.h"
#include "roadslam/registration/robust_kernel.h"

namespace roadslam::odometry {
namespace {

struct Moments {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  int n = 0;
};

/// Two unit vectors spanning the plane orthogonal to unit \p d.
void orthonormalPair(const Eigen::Vector3d& d, Eigen::Vector3d& a, Eigen::Vector3d& b) {
  a = d.unitOrthogonal();
  b = d.cross(a);
}

/// True when the plane through \p mean with normal \p n runs within \p margin_m of a face of its
/// voxel that it nearly parallels: the face then cuts off one side of the range noise and tilts the
/// fitted normal towards the face normal (a bias towards the lidar's axes, not noise).
bool cutByFace(const Eigen::Vector3d& mean, const Eigen::Vector3d& n, const Eigen::Vector3i& key,
               const VerticalStructureParams& p, double margin_m) {
  for (int a = 0; a < 3; ++a) {
    if (std::abs(n(a)) < 0.9) continue;
    const double size = a == 2 ? p.voxel_height_m : p.voxel_m;
    const double lo = key(a) * size;
    if (mean(a) - lo < margin_m || lo + size - mean(a) < margin_m) return true;
  }
  return false;
}

}  // namespace

std::vector<VerticalConstraint> findVerticalStructures(const std::vector<Eigen::Vector3d>& pts,
                                                       const std::vector<uint8_t>& is_ground,
                                                       const Eigen::Vector3d& up, const VerticalStructureParams& p) {
  std::unordered_map<Eigen::Vector3i, Moments, VoxelKeyHash> cells;
  cells.reserve(pts.size() / 4 + 16);
  const Eigen::Array3d inv(1.0 / p.voxel_m, 1.0 / p.voxel_m, 1.0 / p.voxel_height_m);
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!is_ground.empty() && is_ground[i]) continue;
    Moments& m = cells[(pts[i].array() * inv).floor().cast<int>()];
    m.sum += pts[i];
    m.scatter.noalias() += pts[i] * pts[i].transpose();
    ++m.n;
  }
  const double sin_tilt = std::sin(p.max_tilt_rad), cos_tilt = std::cos(p.max_tilt_rad);
  const double plane_ext2 = p.min_plane_extent_m * p.min_plane_extent_m;
  const double line_ext2 = p.min_line_extent_m * p.min_line_extent_m;
  const double lean2 = p.lean_rad * p.lean_rad;
  std::vector<VerticalConstraint> out;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  for (const auto& kv : cells) {
    const Moments& m = kv.second;
    if (m.n < p.min_points) continue;
    const Eigen::Vector3d mean = m.sum / m.n;
    const Eigen::Matrix3d cov = m.scatter / m.n - mean * mean.transpose();
    es.computeDirect(cov);
    const Eigen::Vector3d ev = es.eigenvalues();  // ascending
    if (ev(2) <= 0) continue;
    const double thick2 = std::max(ev(0), p.min_thickness_m * p.min_thickness_m);
    if (ev(1) >= plane_ext2 && ev(0) < p.planarity * ev(1)) {
      // A wall: its normal is horizontal. The normal's tilt towards up is known to
      // thickness^2 / (n * spread^2 along the wall's vertical) [rad^2]: the weight is its inverse.
      const Eigen::Vector3d n = es.eigenvectors().col(0);
      if (std::abs(n.dot(up)) >= sin_tilt || cutByFace(mean, n, kv.first, p, p.face_margin_m)) continue;
      const Eigen::Vector3d v = (up - up.dot(n) * n).normalized();
      out.push_back({n, 1.0 / (thick2 / (m.n * v.dot(cov * v)) + lean2)});
    } else if (ev(2) >= line_ext2 && ev(1) < p.linearity * ev(2)) {
      // A pole or trunk: its axis is vertical, so both normals of the axis are horizontal.
      const Eigen::Vector3d d = es.eigenvectors().col(2);
      if (std::abs(d.dot(up)) > cos_tilt) {
        Eigen::Vector3d a, b;
        orthonormalPair(d, a, b);
        const double w = 1.0 / (std::max(ev(1), p.min_thickness_m * p.min_thickness_m) / (m.n * ev(2)) + lean2);
        out.push_back({a, w});
        out.push_back({b, w});
      }
    }
  }
  return out;
}

Eigen::Matrix3d verticalScatter(const std::vector<VerticalConstraint>& cs, const Eigen::Matrix3d& R,
                                const Eigen::Vector3d& up, double kernel_rad) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  const double s2 = kernel_rad * kernel_rad;
  for (const auto& c : cs) {
    const Eigen::Vector3d n = R * c.normal_lidar;
    const double r = n.dot(up);
    const double k = kernel_rad > 0 ? registration::gemanMcClureWeight(r * r, s2) : 1.0;
    M.noalias() += k * c.weight * n * n.transpose();
  }
  return M;
}

Eigen::Vector3d upFromScatter(const Eigen::Matrix3d& M, const Eigen::Vector3d& hint, Eigen::Vector2d* info_out) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(M);
  Eigen::Vector3d g = es.eigenvectors().col(0);
  if (g.dot(hint) < 0) g = -g;
  if (info_out) *info_out = es.eigenvalues().tail<2>() - Eigen::Vector2d::Constant(es.eigenvalues()(0));
  return g;
}

}  // namespace roadslam::odometry

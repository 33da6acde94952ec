#include "roadslam/registration/fpfh.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "target_impl.h"

namespace roadslam::registration {
namespace {

using Spfh = Fpfh;

/// Neighbours within radius [m], nearest first, at most max_n (0: all); the query itself included.
std::vector<std::pair<uint32_t, double>> radiusNeighbours(const KdTree& tree, const Eigen::Vector3d& q, double radius_m,
                                                          int max_n) {
  std::vector<std::pair<uint32_t, double>> m;
  const nanoflann::SearchParams sp(32, 0.0f, max_n > 0);
  tree.radiusSearch(q.data(), radius_m * radius_m, m, sp);
  if (max_n > 0 && m.size() > static_cast<size_t>(max_n)) m.resize(static_cast<size_t>(max_n));
  return m;
}

/// Rusu 2009 Sec. III: the Darboux frame u = n_s, v = u x (p_t - p_s)/d, w = u x v at the point whose
/// normal makes the smaller angle with the line joining the two (PCL's computePairFeatures); returns
/// false for coincident points.
bool pairFeatures(const Eigen::Vector3d& p1, const Eigen::Vector3d& n1, const Eigen::Vector3d& p2,
                  const Eigen::Vector3d& n2, double f[3]) {
  Eigen::Vector3d dp = p2 - p1;
  const double d = dp.norm();
  if (d <= 0) return false;
  Eigen::Vector3d ns = n1, nt = n2;
  const double a1 = n1.dot(dp) / d, a2 = n2.dot(dp) / d;
  double phi = a1;
  if (std::acos(std::min(1.0, std::abs(a1))) > std::acos(std::min(1.0, std::abs(a2)))) {
    ns = n2;
    nt = n1;
    dp = -dp;
    phi = -a2;
  }
  Eigen::Vector3d v = dp.cross(ns);
  const double vn = v.norm();
  if (vn == 0) {
    f[0] = f[1] = 0;
  } else {
    v /= vn;
    const Eigen::Vector3d w = ns.cross(v);
    f[1] = v.dot(nt);
    f[0] = std::atan2(w.dot(nt), ns.dot(nt));
  }
  f[2] = phi;
  return true;
}

int bin(double x01) { return std::clamp(static_cast<int>(std::floor(11.0 * x01)), 0, 10); }

}  // namespace

PointCloud estimateNormals(const PointCloud& points, double radius_m, const Eigen::Vector3d& viewpoint,
                           int min_neighbours) {
  PointCloud normals(points.size(), Eigen::Vector3d::Zero());
  if (points.empty()) return normals;
  CloudAdaptor ad{&points};
  const KdTree tree(3, ad, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  for (size_t i = 0; i < points.size(); ++i) {
    const auto nb = radiusNeighbours(tree, points[i], radius_m, 0);
    if (static_cast<int>(nb.size()) < std::max(min_neighbours, 3)) continue;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& m : nb) mean += points[m.first];
    mean /= static_cast<double>(nb.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& m : nb) {
      const Eigen::Vector3d d = points[m.first] - mean;
      cov.noalias() += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
    es.computeDirect(cov);
    Eigen::Vector3d n = es.eigenvectors().col(0);
    if (n.dot(viewpoint - points[i]) < 0) n = -n;
    normals[i] = n;
  }
  return normals;
}

// SPFH of every point that is a keypoint or a keypoint's neighbour, then FPFH (Rusu 2009 eq. 4):
// FPFH(p) = SPFH(p) + 1/k sum_i SPFH(p_i) / w_i, w_i the squared distance (Open3D's weighting), each
// group of 11 bins renormalised to 100.
std::vector<Fpfh> computeFpfh(const PointCloud& points, const PointCloud& normals, const std::vector<int>& at,
                              double radius_m, int max_neighbours) {
  std::vector<Fpfh> out(at.size(), Fpfh::Zero());
  if (points.empty() || at.empty()) return out;
  CloudAdaptor ad{&points};
  const KdTree tree(3, ad, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  std::vector<Spfh> spfh(points.size());
  std::vector<uint8_t> done(points.size(), 0);
  auto spfhOf = [&](uint32_t i) -> const Spfh& {
    if (done[i]) return spfh[i];
    done[i] = 1;
    Spfh& h = spfh[i];
    h.setZero();
    if (normals[i].isZero()) return h;
    const auto nb = radiusNeighbours(tree, points[i], radius_m, max_neighbours);
    int used = 0;
    for (const auto& m : nb) used += (m.first != i && !normals[m.first].isZero()) ? 1 : 0;
    if (used == 0) return h;
    const float inc = 100.0f / static_cast<float>(used);
    for (const auto& m : nb) {
      const uint32_t j = m.first;
      if (j == i || normals[j].isZero()) continue;
      double f[3];
      if (!pairFeatures(points[i], normals[i], points[j], normals[j], f)) continue;
      h[bin((f[0] + M_PI) / (2 * M_PI))] += inc;
      h[11 + bin((f[1] + 1) * 0.5)] += inc;
      h[22 + bin((f[2] + 1) * 0.5)] += inc;
    }
    return h;
  };
  for (size_t k = 0; k < at.size(); ++k) {
    const uint32_t i = static_cast<uint32_t>(at[k]);
    if (normals[i].isZero()) continue;
    const auto nb = radiusNeighbours(tree, points[i], radius_m, max_neighbours);
    Fpfh acc = Fpfh::Zero();
    for (const auto& m : nb) {
      if (m.first == i || m.second <= 0 || normals[m.first].isZero()) continue;
      acc += spfhOf(m.first) / static_cast<float>(m.second);
    }
    for (int g = 0; g < 3; ++g) {
      const float s = acc.segment<11>(11 * g).sum();
      if (s > 0) acc.segment<11>(11 * g) *= 100.0f / s;
    }
    out[k] = acc + spfhOf(i);
  }
  return out;
}

}  // namespace roadslam::registration

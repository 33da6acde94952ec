#include "roadslam/preprocess/ransac_ground.h"

#include "param_utils.h"
#include "rng.h"
#include "roadslam/common/param_table.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <sstream>

namespace roadslam::preprocess {
namespace {

Eigen::Vector3d vec(const ScanPoint& p) { return {p.x, p.y, p.z}; }

size_t countInliers(const std::vector<ScanPoint>& pts, const std::vector<uint32_t>& idx,
                    const Eigen::Vector3d& n, double d, double tol) {
  size_t c = 0;
  for (uint32_t i : idx) c += std::abs(n.dot(vec(pts[i])) + d) <= tol;
  return c;
}

/// Least-squares plane through the inliers of (n, d): normal = eigenvector of the smallest
/// eigenvalue of their covariance.
bool refine(const std::vector<ScanPoint>& pts, const RansacGroundParams& prm, Eigen::Vector3d& n,
            double& d) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sq = Eigen::Matrix3d::Zero();
  size_t c = 0;
  for (const auto& p : pts) {
    const Eigen::Vector3d v = vec(p);
    if (std::abs(n.dot(v) + d) > prm.max_distance_m) continue;
    sum += v;
    sq += v * v.transpose();
    ++c;
  }
  if (c < 3) return false;
  const Eigen::Vector3d mean = sum / static_cast<double>(c);
  const Eigen::Matrix3d cov = sq / static_cast<double>(c) - mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  Eigen::Vector3d nn = es.eigenvectors().col(0);
  if (nn.dot(prm.up) < 0) nn = -nn;
  if (std::acos(std::min(1.0, nn.dot(prm.up.normalized()))) > prm.max_angle_rad) return false;
  n = nn;
  d = -n.dot(mean);
  return true;
}
}  // namespace

PlaneFit fitGroundPlaneRansac(const std::vector<ScanPoint>& pts, const RansacGroundParams& prm) {
  PlaneFit fit;
  if (pts.size() < 3) return fit;
  detail::SplitMix64 rng(prm.seed);
  std::vector<uint32_t> eval;
  const size_t n_eval = std::min(pts.size(), static_cast<size_t>(std::max(prm.max_eval_points, 3)));
  for (size_t i = 0; i < n_eval; ++i)
    eval.push_back(n_eval == pts.size() ? static_cast<uint32_t>(i)
                                        : static_cast<uint32_t>(rng.below(pts.size())));
  const Eigen::Vector3d up = prm.up.normalized();
  const double cos_max = std::cos(prm.max_angle_rad);
  size_t best = 0;
  for (int it = 0; it < prm.iterations; ++it) {
    const Eigen::Vector3d a = vec(pts[eval[rng.below(n_eval)]]);
    const Eigen::Vector3d b = vec(pts[eval[rng.below(n_eval)]]);
    const Eigen::Vector3d c = vec(pts[eval[rng.below(n_eval)]]);
    Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    if (len < 1e-9) continue;
    n /= len;
    if (n.dot(up) < 0) n = -n;
    if (n.dot(up) < cos_max) continue;  // orientation constraint: not a ground candidate
    const double d = -n.dot(a);
    const size_t c_in = countInliers(pts, eval, n, d, prm.max_distance_m);
    if (c_in > best) {
      best = c_in;
      fit.normal = n;
      fit.d = d;
      fit.found = true;
    }
  }
  if (!fit.found) return fit;
  refine(pts, prm, fit.normal, fit.d);  // keeps the hypothesis when the refit breaks the constraint
  for (const auto& p : pts) fit.inliers += std::abs(fit.normal.dot(vec(p)) + fit.d) <= prm.max_distance_m;
  return fit;
}

std::vector<uint8_t> labelPlaneInliers(const std::vector<ScanPoint>& pts, const PlaneFit& plane,
                                       double max_distance_m) {
  std::vector<uint8_t> labels(pts.size(), 0);
  if (!plane.found) return labels;
  const float nx = static_cast<float>(plane.normal.x()), ny = static_cast<float>(plane.normal.y());
  const float nz = static_cast<float>(plane.normal.z()), d = static_cast<float>(plane.d);
  const float tol = static_cast<float>(max_distance_m);
  for (size_t i = 0; i < pts.size(); ++i) {
    const auto& p = pts[i];
    labels[i] = std::abs(nx * p.x + ny * p.y + nz * p.z + d) <= tol;
  }
  return labels;
}

size_t removeLabelled(std::vector<ScanPoint>& pts, const std::vector<uint8_t>& labels) {
  size_t w = 0;
  for (size_t i = 0; i < pts.size(); ++i)
    if (!labels[i]) pts[w++] = pts[i];
  const size_t removed = pts.size() - w;
  pts.resize(w);
  return removed;
}

size_t removeGroundRansac(std::vector<ScanPoint>& pts, const RansacGroundParams& prm, PlaneFit* out) {
  const PlaneFit fit = fitGroundPlaneRansac(pts, prm);
  if (out) *out = fit;
  return fit.found ? removeLabelled(pts, labelPlaneInliers(pts, fit, prm.max_distance_m)) : 0;
}

void RansacGroundParams::fields(ParamTable& t) {
  t.numOrAlias("ransac_max_distance_m", "maxD", max_distance_m);
  t.numOrAlias("ransac_max_angle_deg", "maxAngD", max_angle_rad, unit::kDeg);
  t.num("ransac_iterations", iterations);
  t.num("ransac_eval_points", max_eval_points);
  t.num("ransac_seed", seed);
}

void RansacGroundParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                            const std::string& s) {
  loadFields(*this, cfg, s);
  const std::string up_s = readString(cfg, s, "ransac_up", "");
  if (!up_s.empty()) {
    std::istringstream ss(up_s);
    Eigen::Vector3d u;
    detail::require(static_cast<bool>(ss >> u.x() >> u.y() >> u.z()) && u.norm() > 0, s,
                    "ransac_up", "'" + up_s + "' is not a non-zero vector 'x y z'");
    up = u.normalized();
  }
  detail::require(max_distance_m > 0, s, "ransac_max_distance_m", "must be > 0");
  detail::require(max_angle_rad >= 0 && max_angle_rad < M_PI / 2, s, "ransac_max_angle_deg",
                  "must be in [0, 90)");
  detail::require(iterations > 0 && max_eval_points >= 3, s, "ransac_iterations/ransac_eval_points",
                  "must be > 0 and >= 3");
}

void RansacGroundParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  std::ostringstream ss;
  ss << up.x() << ' ' << up.y() << ' ' << up.z();
  cfg.write(s, "ransac_up", ss.str());
}

}  // namespace roadslam::preprocess

#include "roadslam/registration/global_registration.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "solvers.h"

namespace roadslam::registration {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// nanoflann adaptor over FPFH descriptors (33-D, float).
struct FeatureAdaptor {
  const std::vector<Fpfh>* f = nullptr;
  size_t kdtree_get_point_count() const { return f->size(); }
  float kdtree_get_pt(size_t i, size_t d) const { return (*f)[i][static_cast<Eigen::Index>(d)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
using FeatureTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, FeatureAdaptor>,
                                                        FeatureAdaptor, 33, uint32_t>;

}  // namespace

class FeatureIndex {
 public:
  explicit FeatureIndex(std::vector<Fpfh> f)
      : features_(std::move(f)), ad_{&features_}, tree_(33, ad_, nanoflann::KDTreeSingleIndexAdaptorParams(15)) {}
  FeatureIndex(const FeatureIndex&) = delete;
  FeatureIndex& operator=(const FeatureIndex&) = delete;

  /// Nearest descriptor of each query; \p eps > 0 allows an approximate answer within (1 + eps) of the
  /// true distance (Arya et al. 1998, as nanoflann implements it) [-].
  std::vector<uint32_t> nearest(const std::vector<Fpfh>& queries, float eps) const {
    std::vector<uint32_t> nn(queries.size(), 0);
    for (size_t i = 0; i < queries.size(); ++i) nn[i] = nearest(queries[i], eps);
    return nn;
  }
  uint32_t nearest(const Fpfh& query, float eps) const {
    uint32_t nn = 0;
    float d2 = 0;
    nanoflann::KNNResultSet<float, uint32_t> rs(1);
    rs.init(&nn, &d2);
    tree_.findNeighbors(rs, query.data(), nanoflann::SearchParams(32, eps, false));
    return nn;
  }

 private:
  std::vector<Fpfh> features_;
  FeatureAdaptor ad_;
  FeatureTree tree_;
};

namespace {

/// The cloud's cached index, else one built now into \p local.
const FeatureIndex& indexOf(const FeatureCloud& c, std::unique_ptr<FeatureIndex>& local) {
  if (c.index) return *c.index;
  local = std::make_unique<FeatureIndex>(c.features);
  return *local;
}

struct Correspondence {
  Eigen::Vector3d s, t;  ///< source point, target point [m]
};

/// Mutual nearest neighbours in feature space (Zhou et al. 2016, Sec. 3.1: the reciprocity test).
std::vector<Correspondence> mutualMatches(const FeatureCloud& target, const FeatureCloud& source, float eps) {
  std::unique_ptr<FeatureIndex> local_t, local_s;
  const auto s2t = indexOf(target, local_t).nearest(source.features, eps);
  // the reciprocity test reads t2s only at the target features some source feature chose: query those
  // alone (a deterministic search per query, so the same matches as querying every target feature)
  const FeatureIndex& source_index = indexOf(source, local_s);
  constexpr uint32_t kNotQueried = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> t2s(target.features.size(), kNotQueried);
  for (uint32_t t : s2t)
    if (t2s[t] == kNotQueried) t2s[t] = source_index.nearest(target.features[t], eps);
  std::vector<Correspondence> out;
  for (size_t i = 0; i < s2t.size(); ++i) {
    if (t2s[s2t[i]] != i) continue;
    out.push_back({source.points[static_cast<size_t>(source.keypoints[i])],
                   target.points[static_cast<size_t>(target.keypoints[s2t[i]])]});
  }
  return out;
}

/// Least-squares rigid motion (Umeyama 1991, no scale) of the correspondences \p idx.
Eigen::Isometry3d fitRigid(const std::vector<Correspondence>& c, const std::vector<int>& idx) {
  Eigen::Matrix3Xd S(3, idx.size()), T(3, idx.size());
  for (size_t k = 0; k < idx.size(); ++k) {
    S.col(static_cast<Eigen::Index>(k)) = c[static_cast<size_t>(idx[k])].s;
    T.col(static_cast<Eigen::Index>(k)) = c[static_cast<size_t>(idx[k])].t;
  }
  Eigen::Isometry3d out;
  out.matrix() = Eigen::umeyama(S, T, false);
  return out;
}

std::vector<int> supportOf(const std::vector<Correspondence>& c, const Eigen::Isometry3d& T, double d_m) {
  std::vector<int> in;
  const double d2 = d_m * d_m;
  for (size_t i = 0; i < c.size(); ++i)
    if ((T * c[i].s - c[i].t).squaredNorm() < d2) in.push_back(static_cast<int>(i));
  return in;
}

/// Refits a pose on its support until the support stops growing (at most 3 times).
Eigen::Isometry3d refit(const std::vector<Correspondence>& c, Eigen::Isometry3d T, double d_m, int& support) {
  std::vector<int> in = supportOf(c, T, d_m);
  for (int k = 0; k < 3 && in.size() >= 3; ++k) {
    const Eigen::Isometry3d T2 = fitRigid(c, in);
    std::vector<int> in2 = supportOf(c, T2, d_m);
    if (in2.size() < in.size()) break;
    T = T2;
    const bool same = in2.size() == in.size();
    in = std::move(in2);
    if (same) break;
  }
  support = static_cast<int>(in.size());
  return T;
}

struct Hypothesis {
  int support = 0;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
};

bool farApart(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, const GlobalParams& p) {
  return (a.translation() - b.translation()).norm() > p.rival_distance_m ||
         Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() > p.rival_angle_rad;
}

bool edgesAgree(const std::vector<Correspondence>& c, const int k[3], const GlobalParams& p) {
  for (int a = 0; a < 3; ++a) {
    const auto& x = c[static_cast<size_t>(k[a])];
    const auto& y = c[static_cast<size_t>(k[(a + 1) % 3])];
    const double ds = (x.s - y.s).norm(), dt = (x.t - y.t).norm();
    if (ds < p.min_edge_m || dt < p.min_edge_m) return false;
    if (ds < p.edge_similarity * dt || dt < p.edge_similarity * ds) return false;
  }
  return true;
}

/// RANSAC over triplets (Fischler & Bolles 1981) with the adaptive number of draws
/// N = log(1 - p) / log(1 - w^3), w the best support ratio so far (Hartley & Zisserman, alg. 4.5).
std::vector<Hypothesis> ransac(const std::vector<Correspondence>& c, const GlobalParams& p, int& scored) {
  std::mt19937 rng(p.seed);
  std::uniform_int_distribution<int> pick(0, static_cast<int>(c.size()) - 1);
  std::vector<Hypothesis> hyp;
  int best = 0;
  double needed = p.ransac_max_iterations;
  scored = 0;
  for (int it = 0; it < p.ransac_max_iterations && it < needed; ++it) {
    int k[3] = {pick(rng), pick(rng), pick(rng)};
    if (k[0] == k[1] || k[1] == k[2] || k[0] == k[2] || !edgesAgree(c, k, p)) continue;
    const Eigen::Isometry3d T = fitRigid(c, {k[0], k[1], k[2]});
    const int s = static_cast<int>(supportOf(c, T, p.inlier_distance_m).size());
    ++scored;
    if (s < 3) continue;
    hyp.push_back({s, T});
    if (s > best) {
      best = s;
      const double w = static_cast<double>(best) / c.size();
      const double miss = 1.0 - w * w * w;
      needed = miss <= 0 ? 0 : std::log(1.0 - p.ransac_probability) / std::log(miss);
    }
  }
  return hyp;
}

}  // namespace

GlobalParams::GlobalParams() {
  fine.method = Method::IcpPointToPlane;
  fine.max_correspondence_distance_m = 1.0;
  fine.max_iterations = 40;
  fine.max_correction_m = 2.0;
}

void GlobalParams::fields(ParamTable& t) {
  t.num("voxel_m", voxel_m);
  t.num("normal_radius_m", normal_radius_m);
  t.num("feature_radius_m", feature_radius_m);
  t.num("max_feature_neighbours", max_feature_neighbours);
  t.angle("level_normal_deg", level_normal_rad);
  t.num("min_keypoints", min_keypoints);
  t.num("min_correspondences", min_correspondences);
  t.num("match_eps", match_eps);
  t.num("ransac_max_iterations", ransac_max_iterations);
  t.num("ransac_probability", ransac_probability);
  t.num("inlier_distance_m", inlier_distance_m);
  t.num("edge_similarity", edge_similarity);
  t.num("min_edge_m", min_edge_m);
  t.num("min_consensus", min_consensus);
  t.num("rival_distance_m", rival_distance_m);
  t.angle("rival_angle_deg", rival_angle_rad);
  t.num("min_confidence", min_confidence);
  t.num("min_overlap_margin", min_overlap_margin);
  t.num("refine_voxel_m", refine_voxel_m);
  t.num("min_overlap", min_overlap);
  t.flag("reject_degenerate", reject_degenerate);
  t.num("seed", seed);
}

void GlobalParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<GlobalParams>());
  if (voxel_m <= 0 || normal_radius_m <= 0 || feature_radius_m <= 0 || inlier_distance_m <= 0 || refine_voxel_m <= 0 ||
      ransac_max_iterations < 1 || ransac_probability <= 0 || ransac_probability >= 1 || edge_similarity <= 0 ||
      edge_similarity > 1 || min_consensus < 3) {
    throw std::runtime_error("[" + s + "]: *_m and ransac_max_iterations must be > 0, ransac_probability in (0, 1), "
                             "edge_similarity in (0, 1], min_consensus >= 3");
  }
  fine.loadFromConfigFile(cfg, s + "_fine");
}

void GlobalParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  fine.saveToConfigFile(cfg, s + "_fine");
}

namespace {

FeatureCloud featuresOf(const PointCloud& points, const GlobalParams& p, bool as_target) {
  FeatureCloud fc;
  for (const auto& q : points) fc.input_points += q.allFinite() ? 1 : 0;
  fc.points = voxelDownsample(points, p.voxel_m);
  fc.refine_points = voxelDownsample(points, p.refine_voxel_m);
  const PointCloud normals = estimateNormals(fc.points, p.normal_radius_m, Eigen::Vector3d::Zero());
  const double max_nz = std::cos(p.level_normal_rad);
  for (size_t i = 0; i < fc.points.size(); ++i)
    if (!normals[i].isZero() && std::abs(normals[i].z()) < max_nz) fc.keypoints.push_back(static_cast<int>(i));
  fc.features = computeFpfh(fc.points, normals, fc.keypoints, p.feature_radius_m, p.max_feature_neighbours);
  fc.index = std::make_shared<const FeatureIndex>(fc.features);
  if (as_target) fc.refine_target = std::make_shared<const Target>(fc.refine_points, p.fine);
  return fc;
}

}  // namespace

FeatureCloud computeFeatures(const PointCloud& points, const GlobalParams& p, bool as_target) {
  return featuresOf(points, p, as_target);
}

RegistrationResult alignGlobal(const FeatureCloud& target, const FeatureCloud& source, const GlobalParams& p,
                               GlobalDiagnostics* diag) {
  GlobalDiagnostics local;
  GlobalDiagnostics& d = diag ? *diag : local;
  d = GlobalDiagnostics{};
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  const int min_pts = p.fine.min_source_points;
  if (static_cast<int>(source.refine_points.size()) < min_pts || static_cast<int>(target.refine_points.size()) < min_pts) {
    return failed(I, Status::TooFewPoints, "source / target have " + std::to_string(source.refine_points.size()) + " / " +
                                               std::to_string(target.refine_points.size()) +
                                               " points, fewer than min_source_points = " + std::to_string(min_pts));
  }
  const int kp = static_cast<int>(std::min(source.keypoints.size(), target.keypoints.size()));
  if (kp < p.min_keypoints) {
    return failed(I, Status::TooFewPoints, "source / target have " + std::to_string(source.keypoints.size()) + " / " +
                                               std::to_string(target.keypoints.size()) +
                                               " keypoints (points on non-level surfaces), fewer than min_keypoints = " +
                                               std::to_string(p.min_keypoints));
  }
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<Correspondence> c = mutualMatches(target, source, static_cast<float>(p.match_eps));
  d.match_ms = msSince(t0);
  t0 = std::chrono::steady_clock::now();
  d.correspondences = static_cast<int>(c.size());
  if (d.correspondences < p.min_correspondences) {
    return failed(I, Status::TooFewCorrespondences, std::to_string(c.size()) + " mutual feature matches < min_correspondences = " +
                                                        std::to_string(p.min_correspondences));
  }
  const std::vector<Hypothesis> hyp = ransac(c, p, d.hypotheses);
  if (hyp.empty()) return failed(I, Status::NoConsensus, "no triplet of matches agrees on a pose");
  const auto top = std::max_element(hyp.begin(), hyp.end(), [](const auto& a, const auto& b) { return a.support < b.support; });
  d.T_ransac = refit(c, top->T, p.inlier_distance_m, d.consensus);
  // the rival: the best-supported hypothesis far from the best pose, refitted the same way
  const Hypothesis* rival = nullptr;
  for (const auto& h : hyp)
    if (farApart(h.T, d.T_ransac, p) && (!rival || h.support > rival->support)) rival = &h;
  if (rival) {
    d.T_rival = refit(c, rival->T, p.inlier_distance_m, d.rival_consensus);
    if (!farApart(d.T_rival, d.T_ransac, p)) d.rival_consensus = 0;  // it slid onto the best pose
  }
  d.ransac_ms = msSince(t0);
  if (d.consensus < p.min_consensus) {
    return failed(d.T_ransac, Status::NoConsensus, "best pose supported by " + std::to_string(d.consensus) +
                                                       " matches < min_consensus = " + std::to_string(p.min_consensus));
  }
  double confidence = 1.0 - std::min(1.0, static_cast<double>(d.rival_consensus) / d.consensus);
  t0 = std::chrono::steady_clock::now();
  std::unique_ptr<Target> local_target;
  if (!target.refine_target) local_target = std::make_unique<Target>(target.refine_points, p.fine);
  const Target& fine_target = target.refine_target ? *target.refine_target : *local_target;
  RegistrationResult r = align(fine_target, source.refine_points, d.T_ransac, p.fine);
  const double n_src = static_cast<double>(source.refine_points.size());
  if (confidence < p.min_confidence) {
    // the features cannot tell the two poses apart: let the whole clouds decide, each pose refined and
    // judged by its overlap (source points paired within the refinement's reach)
    RegistrationResult rr = align(fine_target, source.refine_points, d.T_rival, p.fine);
    double ov = r.converged ? r.inliers / n_src : 0.0, ov_rival = rr.converged ? rr.inliers / n_src : 0.0;
    if (ov_rival > ov) {
      std::swap(r, rr);
      std::swap(ov, ov_rival);
      std::swap(d.T_ransac, d.T_rival);
    }
    if (ov - ov_rival < p.min_overlap_margin) {
      d.refine_ms = msSince(t0);
      RegistrationResult a = failed(d.T_ransac, Status::Ambiguous, "a pose far away is supported by " +
                                                                      std::to_string(d.rival_consensus) + " matches against " +
                                                                      std::to_string(d.consensus) + ", refined overlaps " +
                                                                      std::to_string(ov) + " / " + std::to_string(ov_rival));
      a.confidence = confidence;
      return a;
    }
    confidence = 1.0 - ov_rival / ov;
  }
  d.refine_ms = msSince(t0);
  r.confidence = confidence;
  if (!r.converged) {
    r.reason = "refinement: " + r.reason;
    return r;
  }
  const double overlap = static_cast<double>(r.inliers) / source.refine_points.size();
  if (p.reject_degenerate && r.degeneracy.degenerate) {
    r.converged = false;
    r.status = Status::Ambiguous;
    r.reason = "the refined alignment leaves " + std::to_string(r.degeneracy.num_weak) +
               " direction(s) unconstrained (degeneracy analysis of the refinement)";
  } else if (overlap < p.min_overlap) {
    r.converged = false;
    r.status = Status::LowOverlap;
    r.reason = "refined pose pairs " + std::to_string(r.inliers) + " of " + std::to_string(source.refine_points.size()) +
               " source points, below min_overlap";
  }
  return r;
}

RegistrationResult alignGlobal(const PointCloud& points_target, const PointCloud& points_source, const GlobalParams& p,
                               GlobalDiagnostics* diagnostics) {
  const auto t0 = std::chrono::steady_clock::now();
  const FeatureCloud target = featuresOf(points_target, p, true), source = featuresOf(points_source, p, false);
  const double features_ms = msSince(t0);
  const RegistrationResult r = alignGlobal(target, source, p, diagnostics);
  if (diagnostics) diagnostics->features_ms = features_ms;
  return r;
}

}  // namespace roadslam::registration

// The only translation unit that includes MRPT's graph-SLAM headers (levmarq.h costs ~4 s to parse).
#include "roadslam/mapping/pose_graph.h"

#include <cerrno>
#include <mrpt/graphs/CNetworkOfPoses.h>
#include <mrpt/graphslam/levmarq.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "ini_keys.h"
#include "pose_graph_solver.h"

namespace roadslam::mapping {
namespace {

mrpt::poses::CPose3D toMrpt(const Eigen::Isometry3d& T) {
  mrpt::math::CMatrixDouble44 M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = T.matrix()(r, c);
  return mrpt::poses::CPose3D::FromHomogeneousMatrix(M);
}

Eigen::Isometry3d toEigen(const mrpt::poses::CPose3D& p) {
  const auto M = p.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = M(r, c);
  return T;
}

/// se(3) residual [t, rotation vector] of the measurement against the estimate (small-error form).
Eigen::Matrix<double, 6, 1> residual(const Eigen::Isometry3d& T_meas, const Eigen::Isometry3d& T_est) {
  return detail::pseudoLog(T_meas.inverse() * T_est);
}

/// The mean eigenvalue of \p B times identity; with \p weak_ratio > 0, eigen-directions below
/// weak_ratio * the largest eigenvalue keep their own value and stay out of the mean.
Eigen::Matrix3d isotropicBlock(const Eigen::Matrix3d& B, double weak_ratio) {
  if (weak_ratio <= 0) return Eigen::Matrix3d::Identity() * B.trace() / 3;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(B);
  const Eigen::Vector3d ev = es.eigenvalues();  // ascending
  double sum = 0;
  int strong = 0;
  for (int i = 0; i < 3; ++i) {
    if (ev(i) >= weak_ratio * ev(2)) {
      sum += ev(i);
      ++strong;
    }
  }
  Eigen::Vector3d out;
  for (int i = 0; i < 3; ++i) out(i) = ev(i) >= weak_ratio * ev(2) ? sum / strong : ev(i);
  return es.eigenvectors() * out.asDiagonal() * es.eigenvectors().transpose();
}

}  // namespace

void PoseGraphParams::fields(ParamTable& t) {
  t.num("max_iterations", max_iterations);
  static const NameTable<GraphOptimizer> optimizers{{GraphOptimizer::Lm, "lm"}, {GraphOptimizer::MrptLevmarq, "mrpt_levmarq"},
                                                      {GraphOptimizer::Ceres, "ceres"}};
  t.choice("optimizer", optimizer, optimizers);
  t.flag("use_registration_information", use_registration_information);
  t.flag("isotropic_information", isotropic_information);
  t.num("isotropic_weak_ratio", isotropic_weak_ratio);
  t.num("odometry_information_scale", odometry_information_scale);
  t.num("odometry_sigma_t_m", odometry_sigma_t_m);
  t.angle("odometry_sigma_r_deg", odometry_sigma_r_rad);
  t.flag("can_edges", can_edges);
  t.num("can_sigma_t_m", can_sigma_t_m);
  t.num("can_sigma_t_per_m", can_sigma_t_per_m);
  t.angle("can_sigma_yaw_deg", can_sigma_yaw_rad);
  t.angle("can_sigma_yaw_deg_per_m", can_sigma_yaw_rad_per_m);
  t.num("can_weak_information", can_weak_information);
}

void PoseGraphParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<PoseGraphParams>());
  if (max_iterations < 1 || odometry_sigma_t_m <= 0 || odometry_sigma_r_rad <= 0 || odometry_information_scale <= 0) {
    throw std::runtime_error("[" + s + "]: max_iterations, odometry_sigma_* and odometry_information_scale must be > 0");
  }
  if (can_sigma_t_m <= 0 || can_sigma_yaw_rad <= 0 || can_sigma_t_per_m < 0 || can_sigma_yaw_rad_per_m < 0 ||
      can_weak_information < 0 || isotropic_weak_ratio < 0 || isotropic_weak_ratio >= 1) {
    throw std::runtime_error("[" + s + "]: can_sigma_t_m and can_sigma_yaw_deg must be > 0, can_*_per_m and can_weak_information >= 0, isotropic_weak_ratio in [0, 1)");
  }
}

void PoseGraphParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

struct PoseGraph::Impl {
  PoseGraphParams p;
  mrpt::graphs::CNetworkOfPoses3DInf graph;
  std::vector<mrpt::graphs::CNetworkOfPoses3DInf::edges_map_t::iterator> edges;
};

PoseGraph::PoseGraph(PoseGraphParams params) : impl_(std::make_unique<Impl>()) {
  impl_->p = params;
  impl_->graph.root = 0;
}
PoseGraph::~PoseGraph() = default;
PoseGraph::PoseGraph(PoseGraph&&) noexcept = default;
PoseGraph& PoseGraph::operator=(PoseGraph&&) noexcept = default;

size_t PoseGraph::addNode(const Eigen::Isometry3d& T_map_node) {
  const size_t id = impl_->graph.nodes.size();
  impl_->graph.nodes[id] = toMrpt(T_map_node);
  return id;
}

size_t PoseGraph::addEdge(size_t from, size_t to, const Eigen::Isometry3d& T_from_to, const Matrix6d& information) {
  if (from >= numNodes() || to >= numNodes()) throw std::out_of_range("PoseGraph::addEdge: unknown node");
  mrpt::poses::CPose3DPDFGaussianInf pdf;
  pdf.mean = toMrpt(T_from_to);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) pdf.cov_inv(r, c) = 0.5 * (information(r, c) + information(c, r));
  impl_->edges.push_back(impl_->graph.edges.insert({{from, to}, pdf}));
  return impl_->edges.size() - 1;
}

void PoseGraph::removeLastEdge() {
  if (impl_->edges.empty()) return;
  impl_->graph.edges.erase(impl_->edges.back());
  impl_->edges.pop_back();
}

OptimizeStats PoseGraph::optimize() {
  OptimizeStats st;
  if (numNodes() < 2 || impl_->edges.empty()) return st;
  const auto t0 = std::chrono::steady_clock::now();
  if (impl_->p.optimizer == GraphOptimizer::MrptLevmarq) {
    mrpt::graphslam::TResultInfoSpaLevMarq info{};
    mrpt::containers::yaml extra = mrpt::containers::yaml::Map();
    extra["max_iterations"] = static_cast<uint64_t>(impl_->p.max_iterations);
    mrpt::graphslam::optimize_graph_spa_levmarq(impl_->graph, info, nullptr, extra);
    st.iterations = static_cast<int>(info.num_iters);
    st.final_error = info.final_total_sq_error;
  } else {
    std::vector<detail::SolverEdge> edges;
    edges.reserve(impl_->edges.size());
    for (const auto& it : impl_->edges) {
      detail::SolverEdge e;
      e.from = it->first.first;
      e.to = it->first.second;
      e.T_from_to = toEigen(it->second.mean);
      for (int r = 0; r < 6; ++r)
        for (int c = 0; c < 6; ++c) e.information(r, c) = it->second.cov_inv(r, c);
      edges.push_back(e);
    }
    PoseVector T = poses();
    const detail::PoseGraphSolver solve =
        impl_->p.optimizer == GraphOptimizer::Ceres ? detail::optimizePosesCeres : detail::optimizePoses;
    const auto r = solve(T, edges, impl_->p.max_iterations);
    setPoses(T);
    st.iterations = r.iterations;
    st.final_error = r.final_cost;
  }
  st.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

size_t PoseGraph::numNodes() const { return impl_->graph.nodes.size(); }
size_t PoseGraph::numEdges() const { return impl_->edges.size(); }
Eigen::Isometry3d PoseGraph::pose(size_t node) const { return toEigen(impl_->graph.nodes.at(node)); }

PoseVector PoseGraph::poses() const {
  PoseVector out;
  out.reserve(numNodes());
  for (const auto& [id, p] : impl_->graph.nodes) out.push_back(toEigen(p));
  return out;
}

void PoseGraph::setPoses(const PoseVector& T_map_nodes) {
  if (T_map_nodes.size() != numNodes()) throw std::invalid_argument("PoseGraph::setPoses: size mismatch");
  for (size_t i = 0; i < T_map_nodes.size(); ++i) impl_->graph.nodes[i] = toMrpt(T_map_nodes[i]);
}

double PoseGraph::edgeChi2(size_t e) const {
  const auto& it = impl_->edges.at(e);
  const Eigen::Isometry3d T_est = pose(it->first.first).inverse() * pose(it->first.second);
  const auto r = residual(toEigen(it->second.mean), T_est);
  Matrix6d I;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) I(a, b) = it->second.cov_inv(a, b);
  return r.dot(I * r);
}

void PoseGraph::saveToTextFile(const std::string& path) const {
  TempFile tmp(path);
  try {
    errno = 0;
    impl_->graph.saveToTextFile(tmp.path());
  } catch (const std::exception&) {
    throw std::runtime_error(tmp.failure("pose graph"));
  }
  tmp.commit();
}

Matrix6d PoseGraph::odometryInformation(const Matrix6d& reg_info) const {
  const auto& p = impl_->p;
  Matrix6d floor = Matrix6d::Zero();
  floor.diagonal() << Eigen::Vector3d::Constant(1.0 / (p.odometry_sigma_t_m * p.odometry_sigma_t_m)),
      Eigen::Vector3d::Constant(1.0 / (p.odometry_sigma_r_rad * p.odometry_sigma_r_rad));
  if (!p.use_registration_information || !reg_info.allFinite() || reg_info.isZero()) return floor;
  // The registration's information is the precision of one scan-to-map match; scaled by the ini,
  // projected onto the PSD cone, plus a thousandth of the fallback so that a degenerate direction
  // (a tunnel) keeps a finite, weak constraint instead of a singular one.
  Matrix6d I = p.odometry_information_scale * 0.5 * (reg_info + reg_info.transpose());
  Eigen::SelfAdjointEigenSolver<Matrix6d> es(I);
  const Eigen::Matrix<double, 6, 1> ev = es.eigenvalues().cwiseMax(0.0);
  I = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
  if (p.isotropic_information) {
    Matrix6d J = Matrix6d::Zero();
    J.topLeftCorner<3, 3>() = isotropicBlock(I.topLeftCorner<3, 3>(), p.isotropic_weak_ratio);
    J.bottomRightCorner<3, 3>() = isotropicBlock(I.bottomRightCorner<3, 3>(), p.isotropic_weak_ratio);
    I = J;
  }
  return I + floor * 1e-3;
}

Matrix6d sourceFrameInformation(const Matrix6d& I_target, const Eigen::Isometry3d& T_target_source) {
  // exp(delta) T = T exp(Ad_T^-1 delta): delta = Ad_T e, so delta^T I delta = e^T (Ad_T^T I Ad_T) e with the
  // SE(3) adjoint in [t, r] order Ad_T = [[R, [t]x R], [0, R]] (first order, as the residual's pseudo-log)
  const Eigen::Matrix3d R = T_target_source.rotation();
  const Eigen::Vector3d t = T_target_source.translation();
  Eigen::Matrix3d tx;
  tx << 0, -t.z(), t.y(), t.z(), 0, -t.x(), -t.y(), t.x(), 0;
  Matrix6d Ad = Matrix6d::Zero();
  Ad.topLeftCorner<3, 3>() = R;
  Ad.topRightCorner<3, 3>() = tx * R;
  Ad.bottomRightCorner<3, 3>() = R;
  return Ad.transpose() * I_target * Ad;
}

Matrix6d PoseGraph::canInformation(double distance_m, const Eigen::Isometry3d& T_base_lidar) const {
  const auto& p = impl_->p;
  const double d = std::abs(distance_m);
  const double var_t = p.can_sigma_t_m * p.can_sigma_t_m + std::pow(p.can_sigma_t_per_m * d, 2);
  const double var_yaw = p.can_sigma_yaw_rad * p.can_sigma_yaw_rad + std::pow(p.can_sigma_yaw_rad_per_m * d, 2);
  Matrix6d I_base = Matrix6d::Zero();
  I_base.diagonal() << 1 / var_t, 1 / var_t, p.can_weak_information, p.can_weak_information, p.can_weak_information,
      1 / var_yaw;
  // SE(3) adjoint of T_base_lidar in [t, r] order: [[R, [t]x R], [0, R]].
  return sourceFrameInformation(I_base, T_base_lidar);
}

Eigen::Isometry3d fuseMeasurements(const Eigen::Isometry3d& T_a, const Matrix6d& I_a, const Eigen::Isometry3d& T_b,
                                   const Matrix6d& I_b) {
  const Eigen::Isometry3d E = T_a.inverse() * T_b;
  const Eigen::AngleAxisd aa(E.rotation());
  Eigen::Matrix<double, 6, 1> d;
  d.head<3>() = E.translation();
  d.tail<3>() = aa.angle() * aa.axis();
  const Eigen::Matrix<double, 6, 1> s = (I_a + I_b).ldlt().solve(I_b * d);
  Eigen::Isometry3d D = Eigen::Isometry3d::Identity();
  D.translation() = s.head<3>();
  if (s.tail<3>().norm() > 0) D.linear() = Eigen::AngleAxisd(s.tail<3>().norm(), s.tail<3>().normalized()).toRotationMatrix();
  return T_a * D;
}

}  // namespace roadslam::mapping

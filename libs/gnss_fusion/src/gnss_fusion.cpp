#include "roadslam/gnss_fusion/gnss_fusion.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SVD>
#include <Eigen/Sparse>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/checked_config.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "gnss_fusion_solver.h"

namespace roadslam::gnss_fusion {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat36 = Eigen::Matrix<double, 3, 6>;

const NameTable<RobustKernel>& kernelNames() {
  static const NameTable<RobustKernel> t{{RobustKernel::None, "none"}, {RobustKernel::Huber, "huber"},
                                         {RobustKernel::Cauchy, "cauchy"}};
  return t;
}

const NameTable<GnssOptimizer>& optimizerNames() {
  static const NameTable<GnssOptimizer> t{{GnssOptimizer::GaussNewton, "gauss_newton"}, {GnssOptimizer::Ceres, "ceres"}};
  return t;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Eigen::Vector3d rotvec(const Eigen::Matrix3d& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

Eigen::Matrix3d expSO3(const Eigen::Vector3d& w) {
  const double a = w.norm();
  return a < 1e-12 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(a, w / a).toRotationMatrix();
}

/// SE(3) adjoint in [t, r] order: [[R, [t]x R], [0, R]].
Matrix6d adjoint(const Eigen::Isometry3d& T) {
  Matrix6d A = Matrix6d::Zero();
  A.topLeftCorner<3, 3>() = T.rotation();
  A.topRightCorner<3, 3>() = skew(T.translation()) * T.rotation();
  A.bottomRightCorner<3, 3>() = T.rotation();
  return A;
}

double kernelWeight(RobustKernel k, double c, double m) {
  switch (k) {
    case RobustKernel::None: return 1.0;
    case RobustKernel::Huber: return m <= c ? 1.0 : c / m;
    case RobustKernel::Cauchy: return 1.0 / (1.0 + (m / c) * (m / c));
  }
  return 1.0;
}

/// Robust yaw + translation fit z ~ Rz(yaw) a + t (horizontal Procrustes, Cauchy IRLS); z from a.
bool fitYawTranslation(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& z,
                       const std::vector<Eigen::Matrix3d>& info, double c, Eigen::Isometry3d& T) {
  const size_t n = a.size();
  std::vector<double> w(n, 1.0);
  T = Eigen::Isometry3d::Identity();
  for (int it = 0; it < 15; ++it) {
    double sw = 0;
    Eigen::Vector3d ma = Eigen::Vector3d::Zero(), mz = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < n; ++k) {
      sw += w[k];
      ma += w[k] * a[k];
      mz += w[k] * z[k];
    }
    if (sw <= 0) return false;
    ma /= sw;
    mz /= sw;
    double s_cos = 0, s_sin = 0, spread = 0;
    for (size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d da = (a[k] - ma).head<2>(), dz = (z[k] - mz).head<2>();
      s_cos += w[k] * da.dot(dz);
      s_sin += w[k] * (da.x() * dz.y() - da.y() * dz.x());
      spread += w[k] * da.squaredNorm();
    }
    if (spread / sw < 1.0) return false;  // < 1 m rms of motion: the heading is not observable
    const double yaw = std::atan2(s_sin, s_cos);
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = mz - T.linear() * ma;
    for (size_t k = 0; k < n; ++k) {
      const Eigen::Vector3d r = T * a[k] - z[k];
      w[k] = kernelWeight(RobustKernel::Cauchy, c, std::sqrt(std::max(0.0, r.dot(info[k] * r))));
    }
  }
  return true;
}

/// Best rigid T with T * A_i ~ B_i over the poses: rotation the SO(3) projection of sum R_B R_A^T,
/// translation the mean of t_B - R t_A.
Eigen::Isometry3d averageTransform(const PoseVector& A, const PoseVector& B) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < A.size(); ++i) M += B[i].rotation() * A[i].rotation().transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d U = svd.matrixU();
    U.col(2) *= -1;
    R = U * svd.matrixV().transpose();
  }
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < A.size(); ++i) t += B[i].translation() - R * A[i].translation();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = t / static_cast<double>(std::max<size_t>(1, A.size()));
  return T;
}

using Matched = detail::MatchedFix;

}  // namespace

void GnssFusionParams::fields(ParamTable& t) {
  t.num("lever_x_m", lever_x_m);
  t.num("lever_y_m", lever_y_m);
  t.num("lever_z_m", lever_z_m);
  t.num("edge_sigma_t_m", edge_sigma_t_m);
  t.num("edge_sigma_t_per_m", edge_sigma_t_per_m);
  t.angle("edge_sigma_r_deg", edge_sigma_r_rad);
  t.angle("edge_sigma_r_deg_per_m", edge_sigma_r_rad_per_m);
  t.num("edge_vertical_scale", edge_vertical_scale);
  t.choice("kernel", kernel, kernelNames());
  t.num("kernel_width", kernel_width);
  t.num("outlier_gate", outlier_gate);
  t.num("max_time_offset_s", max_time_offset_s);
  t.angle("attitude_prior_sigma_deg", attitude_prior_sigma_rad);
  t.num("max_iterations", max_iterations);
  t.choice("optimizer", optimizer, optimizerNames());
  t.num("uere_m", uere_m);
  t.num("fallback_sigma_m", fallback_sigma_m);
  t.flag("receiver_time", receiver_time);
  t.num("online_window_s", online_window_s);
  t.num("online_solve_period_s", online_solve_period_s);
  t.num("online_blend_s", online_blend_s);
  t.num("online_min_path_m", online_min_path_m);
  t.flag("online_yaw_rate_bias", online_yaw_rate_bias);
  t.flag("online_odometry_scale", online_odometry_scale);
  t.num("online_bias_min_path_m", online_bias_min_path_m);
  t.text("live_source_label", live_source_label);
}

void GnssFusionParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<GnssFusionParams>());
  constexpr double kDeg = 180.0 / M_PI;  // angles are checked as written (degrees)
  const std::pair<const char*, double> positive[] = {
      {"edge_sigma_t_m", edge_sigma_t_m},   {"edge_sigma_r_deg", edge_sigma_r_rad * kDeg},
      {"kernel_width", kernel_width},       {"outlier_gate", outlier_gate},
      {"attitude_prior_sigma_deg", attitude_prior_sigma_rad * kDeg},
      {"max_iterations", max_iterations >= 1 ? 1.0 : 0.0},
      {"uere_m", uere_m},                   {"fallback_sigma_m", fallback_sigma_m},
      {"edge_vertical_scale", edge_vertical_scale},
      {"online_window_s", online_window_s}, {"online_solve_period_s", online_solve_period_s}};
  const std::pair<const char*, double> non_negative[] = {
      {"edge_sigma_t_per_m", edge_sigma_t_per_m}, {"edge_sigma_r_deg_per_m", edge_sigma_r_rad_per_m * kDeg},
      {"max_time_offset_s", max_time_offset_s},   {"online_blend_s", online_blend_s},
      {"online_min_path_m", online_min_path_m},   {"online_bias_min_path_m", online_bias_min_path_m}};
  auto refuse = [&](const char* key, const char* bound) {
    const auto* file = dynamic_cast<const CheckedConfig*>(&cfg);
    const std::string at = file ? file->path() + ":" + std::to_string(file->lineOf(s, key)) + ": " : configSource(cfg);
    throw std::runtime_error(at + "[" + s + "] " + key + " = " + cfg.read_string(s, key, "", false) + ": must be " + bound);
  };
  for (const auto& [key, v] : positive)
    if (!(v > 0)) refuse(key, std::string(key) == "max_iterations" ? "at least 1" : "> 0");
  for (const auto& [key, v] : non_negative)
    if (!(v >= 0)) refuse(key, ">= 0");
}

void GnssFusionParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

Eigen::Isometry3d interpolatePose(const std::vector<double>& st, const PoseVector& T, double t) {
  if (T.empty()) return Eigen::Isometry3d::Identity();
  if (t <= st.front()) return T.front();
  if (t >= st.back()) return T.back();
  const size_t j = static_cast<size_t>(std::upper_bound(st.begin(), st.end(), t) - st.begin());
  const size_t i = j - 1;
  const double a = st[j] > st[i] ? (t - st[i]) / (st[j] - st[i]) : 0.0;
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.translation() = (1 - a) * T[i].translation() + a * T[j].translation();
  out.linear() = Eigen::Quaterniond(T[i].rotation()).slerp(a, Eigen::Quaterniond(T[j].rotation())).toRotationMatrix();
  return out;
}

namespace {

/// The factors of one fusion: the fixes matched to nodes, the motion between nodes, the prior.
class Problem {
 public:
  Problem(const std::vector<double>& st, const PoseVector& T_map, const std::vector<GnssFactor>& fixes,
          const GnssFusionParams& p)
      : p_(p), fixes_(fixes) {
    matchFixes(st, T_map);
    motionFactors(T_map);
  }
  const std::vector<Matched>& matched() const { return m_; }
  void setAttitudePrior(const Eigen::Matrix3d& R0) { R0_prior_ = R0; }
  /// The factors as the other solvers take them (gnss_fusion_solver.h).
  detail::GnssFactors factors() const { return {fixes_, m_, Z_, I_, R0_prior_}; }

  /// One Gauss-Newton step on \p T with the kernel's weights at \p T (IRLS); false when the normal
  /// equations are singular. \p max_step: the largest translation step [m].
  bool step(PoseVector& T, double& max_step) const {
    const size_t N = T.size();
    const int n = static_cast<int>(6 * N);
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(N * 36 * 4 + m_.size() * 36 + 4);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
    auto addBlock = [&](size_t r, size_t c, const Matrix6d& B) {
      for (int x = 0; x < 6; ++x)
        for (int y = 0; y < 6; ++y)
          if (B(x, y) != 0) trip.emplace_back(static_cast<int>(6 * r) + x, static_cast<int>(6 * c) + y, B(x, y));
    };
    for (size_t i = 0; i + 1 < N; ++i) {  // motion factors
      const Eigen::Isometry3d A = T[i].inverse() * T[i + 1];
      const Eigen::Isometry3d E = Z_[i].inverse() * A;
      Vec6 e;
      e << E.translation(), rotvec(E.rotation());
      const Matrix6d Ji = -adjoint(A.inverse());
      const Matrix6d& L = I_[i];
      addBlock(i, i, Ji.transpose() * L * Ji);
      addBlock(i, i + 1, Ji.transpose() * L);
      addBlock(i + 1, i, L * Ji);
      addBlock(i + 1, i + 1, L);
      b.segment<6>(static_cast<int>(6 * i)) += Ji.transpose() * L * e;
      b.segment<6>(static_cast<int>(6 * (i + 1))) += L * e;
    }
    for (const auto& f : m_) {  // GNSS factors, reweighted
      const Eigen::Matrix3d R = T[f.node].rotation();
      const Eigen::Vector3d r = R * f.p + T[f.node].translation() - fixes_[f.fix].p_enu;
      const double w = kernelWeight(p_.kernel, p_.kernel_width, std::sqrt(std::max(0.0, r.dot(f.info * r))));
      Mat36 J;
      J.leftCols<3>() = R;
      J.rightCols<3>() = -R * skew(f.p);
      const Eigen::Matrix3d L = w * f.info;
      addBlock(f.node, f.node, J.transpose() * L * J);
      b.segment<6>(static_cast<int>(6 * f.node)) += J.transpose() * L * r;
    }
    {  // roll / pitch of the first node (node-frame x and y of the rotation change since the start)
      const double info_att = 1.0 / (p_.attitude_prior_sigma_rad * p_.attitude_prior_sigma_rad);
      const Eigen::Vector3d e = rotvec(R0_prior_.transpose() * T[0].rotation());
      Matrix6d B = Matrix6d::Zero();
      B(3, 3) = B(4, 4) = info_att;
      addBlock(0, 0, B);
      b(3) += info_att * e.x();
      b(4) += info_att * e.y();
    }
    for (int x = 0; x < n; ++x) trip.emplace_back(x, x, 1e-9);  // a yaw left free by a standstill stays finite
    Eigen::SparseMatrix<double> H(n, n);
    H.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(H);
    if (ldlt.info() != Eigen::Success) return false;
    const Eigen::VectorXd dx = ldlt.solve(-b);
    max_step = 0;
    for (size_t i = 0; i < N; ++i) {
      const Vec6 d = dx.segment<6>(static_cast<int>(6 * i));
      T[i].translation() += T[i].rotation() * d.head<3>();
      T[i].linear() = T[i].rotation() * expSO3(d.tail<3>());
      max_step = std::max(max_step, d.head<3>().norm());
    }
    return true;
  }

 private:
  /// Each fix on its nearest node in time, the antenna carried from the fix's time to the node's.
  void matchFixes(const std::vector<double>& st, const PoseVector& T_map) {
    const size_t N = T_map.size();
    for (size_t k = 0; k < fixes_.size(); ++k) {
      const double t = fixes_[k].t_s;
      if (N == 0 || t < st.front() - p_.max_time_offset_s || t > st.back() + p_.max_time_offset_s) continue;
      const size_t j = static_cast<size_t>(std::lower_bound(st.begin(), st.end(), t) - st.begin());
      size_t i = std::min(j, N - 1);
      if (j > 0 && (j == N || std::abs(st[j - 1] - t) < std::abs(st[j] - t))) i = j - 1;
      if (std::abs(st[i] - t) > p_.max_time_offset_s) continue;
      const Eigen::Vector3d p_node = T_map[i].inverse() * (interpolatePose(st, T_map, t) * p_.lever());
      const Eigen::Matrix3d C = 0.5 * (fixes_[k].cov + fixes_[k].cov.transpose());
      if (!C.allFinite() || C.determinant() <= 0) continue;
      m_.push_back({k, i, p_node, C.inverse()});
    }
  }
  /// The trajectory's motion between consecutive nodes and its information (Params edge_sigma_*).
  void motionFactors(const PoseVector& T_map) {
    const double k2 = p_.edge_vertical_scale * p_.edge_vertical_scale;
    for (size_t i = 0; i + 1 < T_map.size(); ++i) {
      Z_.push_back(T_map[i].inverse() * T_map[i + 1]);
      const double d = Z_.back().translation().norm();
      const double vt = p_.edge_sigma_t_m * p_.edge_sigma_t_m + std::pow(p_.edge_sigma_t_per_m * d, 2);
      const double vr = p_.edge_sigma_r_rad * p_.edge_sigma_r_rad + std::pow(p_.edge_sigma_r_rad_per_m * d, 2);
      Matrix6d I = Matrix6d::Zero();
      I.diagonal() << 1 / vt, 1 / vt, 1 / (vt * k2), 1 / (vr * k2), 1 / (vr * k2), 1 / vr;
      I_.push_back(I);
    }
  }

  const GnssFusionParams& p_;
  const std::vector<GnssFactor>& fixes_;
  std::vector<Matched> m_;
  PoseVector Z_;
  std::vector<Matrix6d, Eigen::aligned_allocator<Matrix6d>> I_;
  Eigen::Matrix3d R0_prior_ = Eigen::Matrix3d::Identity();
};

}  // namespace

GnssFusionResult fuseGnss(const std::vector<double>& st, const PoseVector& T_map, const std::vector<GnssFactor>& fixes,
                          const GnssFusionParams& p) {
  const auto t0 = std::chrono::steady_clock::now();
  if (st.size() != T_map.size()) throw std::invalid_argument("fuseGnss: stamps and poses differ in size");
  GnssFusionResult res;
  res.fix_use.assign(fixes.size(), FixUse::Unmatched);
  const size_t N = T_map.size();
  // 1. each fix on its nearest node; the motion factors
  Problem problem(st, T_map, fixes, p);
  const std::vector<Matched>& m = problem.matched();
  // 2. the start: a robust yaw + translation fit of the antenna path to the fixes
  std::vector<Eigen::Vector3d> a, z;
  std::vector<Eigen::Matrix3d> info;
  for (const auto& f : m) {
    a.push_back(T_map[f.node] * f.p);
    z.push_back(fixes[f.fix].p_enu);
    info.push_back(f.info);
  }
  if (m.size() < 3 || !fitYawTranslation(a, z, info, p.kernel_width, res.T_enu_map_initial)) {
    res.status = m.size() < 3 ? "fewer than 3 fixes within the trajectory's time span" : "too little motion to observe the heading";
    res.unmatched = fixes.size();
    res.T_enu_node = T_map;
    res.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return res;
  }
  PoseVector T(N);
  for (size_t i = 0; i < N; ++i) T[i] = res.T_enu_map_initial * T_map[i];
  problem.setAttitudePrior(T[0].rotation());
  // 3. Gauss-Newton with the kernel's weights recomputed every iteration (IRLS), or the same factors on Ceres
  if (p.optimizer == GnssOptimizer::Ceres) {
    const detail::GnssSolve s = detail::solveGnssCeres(problem.factors(), p, T);
    res.iterations = s.iterations;
    res.converged = s.converged;
  }
  for (int it = 0; p.optimizer == GnssOptimizer::GaussNewton && it < p.max_iterations; ++it) {
    double max_step = 0;
    if (!problem.step(T, max_step)) {
      res.status = "the normal equations are singular";
      break;
    }
    res.iterations = it + 1;
    if (max_step < 1e-4 && it > 2) {  // the weights settle in a few more iterations than the poses
      res.converged = true;
      break;
    }
  }
  // 4. what each fix became, and the map -> ENU transform over the fused poses
  double sq = 0;
  for (size_t k = 0; k < m.size(); ++k) {
    const auto& f = m[k];
    const Eigen::Vector3d r = T[f.node] * f.p - fixes[f.fix].p_enu;
    const double maha = std::sqrt(std::max(0.0, r.dot(f.info * r)));
    const bool in = maha <= p.outlier_gate;
    res.fix_use[f.fix] = in ? FixUse::Used : FixUse::Rejected;
    if (in) sq += r.head<2>().squaredNorm();
    ++(in ? res.used : res.rejected);
  }
  res.unmatched = fixes.size() - m.size();
  res.rms_inlier_m = res.used ? std::sqrt(sq / static_cast<double>(res.used)) : 0.0;
  res.T_enu_map = averageTransform(T_map, T);
  res.T_enu_node = std::move(T);
  res.ok = res.status.empty();
  if (res.ok) res.status = "ok";
  res.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace roadslam::gnss_fusion

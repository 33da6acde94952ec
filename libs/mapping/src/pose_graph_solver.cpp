#include "pose_graph_solver.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>

namespace roadslam::mapping::detail {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// pexp([rho; w]) = (Exp(w), rho): MRPT's pseudo-exponential (translation as is).
Eigen::Isometry3d pseudoExp(const Vector6d& d) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = d.head<3>();
  const double a = d.tail<3>().norm();
  if (a > 0) T.linear() = Eigen::AngleAxisd(a, d.tail<3>() / a).toRotationMatrix();
  return T;
}

Vector6d residual(const SolverEdge& e, const Eigen::Isometry3d& Ti, const Eigen::Isometry3d& Tj) {
  return pseudoLog(e.T_from_to.inverse() * Ti.inverse() * Tj);
}

double cost(const PoseVector& T, const std::vector<SolverEdge>& edges) {
  double F = 0;
  for (const auto& e : edges) {
    const Vector6d r = residual(e, T[e.from], T[e.to]);
    F += r.dot(e.information * r);
  }
  return F;
}

/// de/d(delta_i) and de/d(delta_j) by central differences (h: 1e-6, truncation ~h^2).
void jacobians(const SolverEdge& e, const Eigen::Isometry3d& Ti, const Eigen::Isometry3d& Tj, Matrix6d& Ji, Matrix6d& Jj) {
  constexpr double h = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vector6d d = Vector6d::Zero();
    d(k) = h;
    Ji.col(k) = (residual(e, Ti * pseudoExp(d), Tj) - residual(e, Ti * pseudoExp(-d), Tj)) / (2 * h);
    Jj.col(k) = (residual(e, Ti, Tj * pseudoExp(d)) - residual(e, Ti, Tj * pseudoExp(-d))) / (2 * h);
  }
}

/// Gauss-Newton system H = sum J^T W J, g = sum J^T W e over the free nodes (node k >= 1 at 6(k-1)).
void normalEquations(const PoseVector& T, const std::vector<SolverEdge>& edges, std::vector<Eigen::Triplet<double>>& H,
                     Eigen::VectorXd& g) {
  H.clear();
  g.setZero(static_cast<Eigen::Index>(6 * (T.size() - 1)));
  auto addBlock = [&H](size_t a, size_t b, const Matrix6d& M) {
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c)
        H.emplace_back(static_cast<int>(6 * (a - 1)) + r, static_cast<int>(6 * (b - 1)) + c, M(r, c));
  };
  for (const auto& e : edges) {
    Matrix6d Ji, Jj;
    jacobians(e, T[e.from], T[e.to], Ji, Jj);
    const Vector6d r = residual(e, T[e.from], T[e.to]);
    const size_t n[2] = {e.from, e.to};
    const Matrix6d* J[2] = {&Ji, &Jj};
    for (int a = 0; a < 2; ++a) {
      if (n[a] == 0) continue;  // the fixed root
      g.segment<6>(static_cast<Eigen::Index>(6 * (n[a] - 1))) += J[a]->transpose() * e.information * r;
      for (int b = 0; b < 2; ++b)
        if (n[b] != 0) addBlock(n[a], n[b], J[a]->transpose() * e.information * *J[b]);
    }
  }
}

}  // namespace

Vector6d pseudoLog(const Eigen::Isometry3d& T) {
  Vector6d e;
  const Eigen::AngleAxisd aa(T.rotation());
  e.head<3>() = T.translation();
  e.tail<3>() = aa.angle() * aa.axis();
  return e;
}

SolverResult optimizePoses(PoseVector& T, const std::vector<SolverEdge>& edges, int max_iterations) {
  SolverResult out;
  out.initial_cost = out.final_cost = cost(T, edges);
  if (T.size() < 2 || edges.empty()) return out;
  const auto n = static_cast<Eigen::Index>(6 * (T.size() - 1));
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd g;
  Eigen::SparseMatrix<double> H(n, n);
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  double F = out.initial_cost, lambda = 1e-4;
  bool relinearize = true, analysed = false;
  for (int it = 0; it < max_iterations; ++it) {
    out.iterations = it + 1;
    if (relinearize) {
      normalEquations(T, edges, trip, g);
      // every diagonal entry present, so the sparsity pattern never changes (one symbolic analysis)
      for (Eigen::Index k = 0; k < n; ++k) trip.emplace_back(static_cast<int>(k), static_cast<int>(k), 0.0);
      H.setFromTriplets(trip.begin(), trip.end());
      relinearize = false;
    }
    Eigen::SparseMatrix<double> A = H;
    // Marquardt's scaling: damping proportional to each variable's own curvature, so metres and
    // radians, weak and strong edges are damped alike (floor: a variable no edge reaches)
    for (Eigen::Index k = 0; k < n; ++k) A.coeffRef(k, k) += lambda * std::max(H.coeff(k, k), 1e-9);
    if (!analysed) {
      ldlt.analyzePattern(A);
      analysed = true;
    }
    ldlt.factorize(A);
    if (ldlt.info() != Eigen::Success) {
      lambda *= 10;
      continue;
    }
    const Eigen::VectorXd delta = ldlt.solve(-g);
    PoseVector trial = T;
    for (size_t k = 1; k < T.size(); ++k) trial[k] = T[k] * pseudoExp(delta.segment<6>(static_cast<Eigen::Index>(6 * (k - 1))));
    const double F_trial = cost(trial, edges);
    if (F_trial < F) {
      const double gain = F - F_trial;
      T.swap(trial);
      F = F_trial;
      lambda = std::max(lambda * 0.1, 1e-12);
      relinearize = true;
      // converged: the cost stopped falling (relative 1e-12) or the step is below a micrometre / microradian
      if (gain <= 1e-12 * F || delta.lpNorm<Eigen::Infinity>() < 1e-9) break;
    } else {
      lambda *= 10;
      if (lambda > 1e12) break;  // no step lowers the cost: at a minimum within rounding
    }
  }
  out.final_cost = F;
  return out;
}

}  // namespace roadslam::mapping::detail

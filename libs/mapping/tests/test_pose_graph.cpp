// PoseGraph: a ring of poses whose odometry has a heading bias is pulled back to the truth by one
// loop edge; the text graph reads back with MRPT's own loader; CAN-edge information and parameters.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/graphs/CNetworkOfPoses.h>

#include <cmath>
#include <filesystem>

#include "roadslam/mapping/pose_graph.h"

using namespace roadslam::mapping;

namespace {

/// Poses on a circle of radius 20 m, 60 nodes, heading along the circle.
PoseVector truth() {
  PoseVector v;
  for (int i = 0; i < 60; ++i) {
    const double a = 2 * M_PI * i / 60;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() << 20 * std::sin(a), 20 - 20 * std::cos(a), 0;
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    v.push_back(T);
  }
  return v;
}

Matrix6d info() {
  Matrix6d I = Matrix6d::Zero();
  I.diagonal() << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;
  return I;
}

PoseGraph ringWithDrift(const PoseVector& gt, GraphOptimizer optimizer = GraphOptimizer::Lm) {
  PoseGraphParams p;
  p.optimizer = optimizer;
  PoseGraph g(p);
  Eigen::Isometry3d T = gt[0];
  g.addNode(T);
  const Eigen::Isometry3d bias(Eigen::AngleAxisd(0.004, Eigen::Vector3d::UnitZ()));
  for (size_t i = 1; i < gt.size(); ++i) {
    const Eigen::Isometry3d d = gt[i - 1].inverse() * gt[i] * bias;
    T = T * d;
    g.addNode(T);
    g.addEdge(i - 1, i, d, info());
  }
  return g;
}

double maxError(const PoseGraph& g, const PoseVector& gt) {
  double e = 0;
  for (size_t i = 0; i < gt.size(); ++i) e = std::max(e, (g.pose(i).translation() - gt[i].translation()).norm());
  return e;
}

}  // namespace

// The oracle tests run on each solver ([pose_graph] optimizer): the own LM and Ceres.
class PoseGraphSolver : public ::testing::TestWithParam<GraphOptimizer> {};
INSTANTIATE_TEST_SUITE_P(Optimizers, PoseGraphSolver, ::testing::Values(GraphOptimizer::Lm, GraphOptimizer::Ceres),
                         [](const auto& info) { return info.param == GraphOptimizer::Ceres ? "ceres" : "lm"; });

TEST_P(PoseGraphSolver, LoopEdgeRemovesHeadingDrift) {
  const auto gt = truth();
  PoseGraph g = ringWithDrift(gt, GetParam());
  const double before = maxError(g, gt);
  g.addEdge(gt.size() - 1, 0, gt.back().inverse() * gt[0], info());
  const auto st = g.optimize();
  const double after = maxError(g, gt);
  std::printf("max position error %.3f m -> %.3f m (%d iterations)\n", before, after, st.iterations);
  EXPECT_GT(before, 3.0);
  EXPECT_LT(after, 0.1 * before);
  // the loop edge holds like any odometry edge: its chi2 is of the order of theirs
  double odo_chi2 = 0;
  for (size_t e = 0; e + 1 < g.numEdges(); ++e) odo_chi2 = std::max(odo_chi2, g.edgeChi2(e));
  EXPECT_LT(g.edgeChi2(g.numEdges() - 1), 3 * odo_chi2 + 1e-9);
}

TEST_P(PoseGraphSolver, RemoveLastEdgeAndRestore) {
  const auto gt = truth();
  PoseGraph g = ringWithDrift(gt, GetParam());
  const auto before = g.poses();
  g.addEdge(gt.size() - 1, 0, gt.back().inverse() * gt[0], info());
  g.optimize();
  g.removeLastEdge();
  g.setPoses(before);
  EXPECT_EQ(g.numEdges(), gt.size() - 1);
  EXPECT_LT((g.pose(30).translation() - before[30].translation()).norm(), 1e-9);
  g.optimize();  // odometry only: nothing to change
  EXPECT_LT((g.pose(30).translation() - before[30].translation()).norm(), 1e-6);
}

TEST(PoseGraph, TextFileReadsBackWithMrpt) {
  const auto gt = truth();
  PoseGraph g = ringWithDrift(gt);
  g.addEdge(gt.size() - 1, 0, gt.back().inverse() * gt[0], info());
  const std::string path = std::string(ROADSLAM_BINARY_DIR) + "/test-out-posegraph.graph";
  g.saveToTextFile(path);
  mrpt::graphs::CNetworkOfPoses3DInf m;
  m.loadFromTextFile(path);
  ASSERT_EQ(m.nodeCount(), gt.size());
  EXPECT_EQ(m.edgeCount(), gt.size());
  for (size_t i = 0; i < gt.size(); i += 7) {
    const auto& p = m.nodes.at(i);
    EXPECT_NEAR(p.x(), g.pose(i).translation().x(), 1e-4);
    EXPECT_NEAR(p.y(), g.pose(i).translation().y(), 1e-4);
  }
  std::filesystem::remove(path);
}

// canInformation against an independent first-order computation: a small lidar-frame error E_l
// seen from the base is E_b = T_base_lidar * E_l * T_base_lidar^-1 (matrix products, no adjoint);
// its energy under the base-frame information must equal the lidar-frame quadratic form.
TEST(PoseGraph, CanInformationIsTheBaseInformationMovedThroughTheMounting) {
  PoseGraphParams p;
  p.can_sigma_t_m = 0.02;
  p.can_sigma_t_per_m = 0.01;
  p.can_sigma_yaw_rad = 0.001;
  p.can_sigma_yaw_rad_per_m = 0.0005;
  p.can_weak_information = 1e-4;
  const PoseGraph g(p);
  const double d = 3.0;
  const double it = 1 / (0.02 * 0.02 + 0.03 * 0.03), iyaw = 1 / (0.001 * 0.001 + 0.0015 * 0.0015);
  // identity mounting: the base information itself
  const Matrix6d I0 = g.canInformation(d, Eigen::Isometry3d::Identity());
  Eigen::Matrix<double, 6, 1> diag;
  diag << it, it, 1e-4, 1e-4, 1e-4, iyaw;
  EXPECT_LT((I0.diagonal() - diag).norm(), 1e-9 * it);
  EXPECT_LT((I0 - Matrix6d(diag.asDiagonal())).norm(), 1e-9 * it);
  // a roof lidar 1.2 m ahead, 1.9 m up, turned 30 deg and tilted 2 deg
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = (Eigen::AngleAxisd(0.5236, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.035, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  X.translation() << 1.2, 0.1, 1.9;
  const Matrix6d I = g.canInformation(d, X);
  std::srand(3);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix<double, 6, 1> e_l = Eigen::Matrix<double, 6, 1>::Random() * 1e-5;
    Eigen::Isometry3d E_l = Eigen::Isometry3d::Identity();
    E_l.translation() = e_l.head<3>();
    E_l.linear() = Eigen::AngleAxisd(e_l.tail<3>().norm(), e_l.tail<3>().normalized()).toRotationMatrix();
    const Eigen::Isometry3d E_b = X * E_l * X.inverse();
    Eigen::Matrix<double, 6, 1> e_b;
    const Eigen::AngleAxisd aa(E_b.rotation());
    e_b.head<3>() = E_b.translation();
    e_b.tail<3>() = aa.angle() * aa.axis();
    const double energy_base = e_b.dot(diag.asDiagonal() * e_b), energy_lidar = e_l.dot(I * e_l);
    EXPECT_NEAR(energy_lidar, energy_base, 1e-3 * energy_base + 1e-12) << "sample " << k;
  }
}

TEST(PoseGraph, CanParamsRoundTripAndRejectBadSigmas) {
  PoseGraphParams p;
  p.can_edges = true;
  p.can_sigma_yaw_rad = 0.002;
  p.can_sigma_t_per_m = 0.02;
  mrpt::config::CConfigFileMemory cfg;
  p.saveToConfigFile(cfg);
  PoseGraphParams q;
  q.loadFromConfigFile(cfg);
  EXPECT_TRUE(q.can_edges);
  EXPECT_NEAR(q.can_sigma_yaw_rad, 0.002, 1e-7);  // the ini holds degrees with 6 digits
  EXPECT_NEAR(q.can_sigma_t_per_m, 0.02, 1e-12);
  cfg.write("pose_graph", "can_sigma_t_m", std::string("0"));
  EXPECT_THROW(q.loadFromConfigFile(cfg), std::runtime_error);
}
// fuseMeasurements against the scalar information-weighted mean (translation-only measurements with
// diagonal information), and the rotation part against the weighted mean of two yaw angles.
TEST(PoseGraph, FusedMeasurementIsTheInformationWeightedMean) {
  Eigen::Isometry3d A = Eigen::Isometry3d::Identity(), B = Eigen::Isometry3d::Identity();
  A.translation() << 1.0, 0.2, 0.0;
  B.translation() << 1.3, 0.1, 0.5;
  Matrix6d Ia = Matrix6d::Zero(), Ib = Matrix6d::Zero();
  Ia.diagonal() << 0.4, 1e4, 1e4, 1e6, 1e6, 1e6;   // a: x barely measured (a tunnel's axis)
  Ib.diagonal() << 1600, 1600, 1e-4, 1e-4, 1e-4, 1e5;  // b: planar wheel odometry
  const Eigen::Isometry3d F = fuseMeasurements(A, Ia, B, Ib);
  for (int k = 0; k < 3; ++k) {
    const double w = Ib(k, k) / (Ia(k, k) + Ib(k, k));
    EXPECT_NEAR(F.translation()(k), A.translation()(k) + w * (B.translation()(k) - A.translation()(k)), 1e-9) << k;
  }
  EXPECT_NEAR(F.translation().x(), 1.3, 1e-3);  // the wheels decide the unmeasured axis
  EXPECT_NEAR(F.translation().z(), 0.0, 1e-6);  // the scans decide what the wheels cannot see
  Eigen::Isometry3d Ra = Eigen::Isometry3d::Identity(), Rb = Eigen::Isometry3d::Identity();
  Ra.linear() = Eigen::AngleAxisd(0.10, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Rb.linear() = Eigen::AngleAxisd(0.16, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Matrix6d Iy = Matrix6d::Identity() * 1e4;
  Matrix6d Iy3 = Iy * 3;
  const Eigen::Isometry3d G = fuseMeasurements(Ra, Iy, Rb, Iy3);
  EXPECT_NEAR(Eigen::AngleAxisd(G.rotation()).angle(), 0.10 + 0.75 * 0.06, 1e-9);
  EXPECT_LT(G.translation().norm(), 1e-12);
}

namespace {

/// A hilly ring: 400 poses on a circle of radius 150 m (a keyframe every 2.4 m of a ~1 km loop) whose
/// height and pitch vary (3D, not planar).
PoseVector hillyTruth() {
  PoseVector v;
  const int N = 400;
  const double R = 150;
  for (int i = 0; i < N; ++i) {
    const double a = 2 * M_PI * i / N;
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() << R * std::sin(a), R - R * std::cos(a), 3 * std::sin(2 * a);
    T.linear() = (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.2 * std::cos(2 * a), Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(0.05 * std::sin(a), Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    v.push_back(T);
  }
  return v;
}

/// A symmetric positive definite 6x6 with off-diagonal terms, eigenvalues scale * [0.1, 1] (a scan
/// registration's information is anisotropic and couples translation and rotation).
Matrix6d anisotropicInformation(double scale, unsigned seed) {
  std::srand(seed);
  const Matrix6d A = Matrix6d::Random();
  const Eigen::HouseholderQR<Matrix6d> qr(A);
  const Matrix6d Q = qr.householderQ();
  Eigen::Matrix<double, 6, 1> ev;
  ev << 0.1, 0.25, 0.4, 0.6, 0.8, 1.0;
  return scale * Q * ev.asDiagonal() * Q.transpose();
}

}  // namespace

// Every edge exact (the true relative pose), so the optimum is the truth itself whatever the
// information; the initial estimate drifted in heading and pitch by an odometry bias (56 m off at the
// loop). The optimiser must return the truth with the loop edge at the odometry's information and at a
// scan registration's full information (1e6, 1e8, anisotropic), with edges in either direction.
// MRPT 2.5.8's optimize_graph_spa_levmarq (POSE_GRAPH_MRPT=1 runs it here) leaves the graph 56 m off at
// 1e6 and 1e8: its first step raises the unweighted error, is refused, and it never recovers
// (pose_graph_solver.h).
TEST_P(PoseGraphSolver, ExactEdgesGiveTheTruthAtAnyLoopInformation) {
  const PoseVector gt = hillyTruth();
  // 0.001 rad of heading and 0.0003 rad of pitch per edge: 56 m off at the loop
  const Eigen::Isometry3d bias(Eigen::AngleAxisd(0.001, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.0003, Eigen::Vector3d::UnitY()));
  for (double loop_scale : {1e4, 1e6, 1e8}) {
    for (bool reversed : {false, true}) {
      SCOPED_TRACE("loop information " + std::to_string(loop_scale) + (reversed ? ", edges reversed" : ""));
      PoseGraphParams gp;
      gp.optimizer = GetParam();
      if (getenv("POSE_GRAPH_MRPT")) gp.optimizer = GraphOptimizer::MrptLevmarq;  // the old optimiser, for comparison
      PoseGraph g(gp);
      Eigen::Isometry3d T = gt[0];
      g.addNode(T);
      for (size_t i = 1; i < gt.size(); ++i) {
        const Eigen::Isometry3d d = gt[i - 1].inverse() * gt[i];
        T = T * d * bias;  // drifted initial estimate
        g.addNode(T);
        // odd edges reversed: the measurement of i -> i-1
        if (reversed && i % 2 == 1) g.addEdge(i, i - 1, d.inverse(), info());
        else g.addEdge(i - 1, i, d, info());
      }
      const size_t last = gt.size() - 1;
      const Matrix6d I_loop = anisotropicInformation(loop_scale, 7);
      if (reversed) g.addEdge(0, last, gt[0].inverse() * gt[last], I_loop);
      else g.addEdge(last, 0, gt[last].inverse() * gt[0], I_loop);
      const double before = maxError(g, gt);
      const auto st = g.optimize();
      double worst_rad = 0;
      for (size_t i = 0; i < gt.size(); ++i)
        worst_rad = std::max(worst_rad, Eigen::AngleAxisd(gt[i].linear().transpose() * g.pose(i).linear()).angle());
      std::printf("loop information %.0e%s: max position error %.3f m -> %.2e m, rotation %.2e rad (%d iterations)\n",
                  loop_scale, reversed ? " reversed" : "", before, maxError(g, gt), worst_rad, st.iterations);
      EXPECT_GT(before, 50.0);
      EXPECT_LT(maxError(g, gt), 1e-4);
      EXPECT_LT(worst_rad, 1e-6);
    }
  }
}

// A registration's information (left perturbations in the target frame, registration.h) moved to the
// graph's residual frame (right perturbations, the source's), against the point-to-plane Hessian built
// directly in the source frame from the same pairs: x = T p, r = n.(x - q); target frame J = [n; x x n],
// source frame (x = T pexp(e) p) J = [R^T n; p x R^T n]. A turned loop (120 deg) 8 m away.
TEST(PoseGraph, LoopInformationMovesToTheQueryFrame) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = (Eigen::AngleAxisd(2.1, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX())).toRotationMatrix();
  T.translation() << 8, -3, 0.4;
  std::srand(11);
  Matrix6d H_target = Matrix6d::Zero(), H_source = Matrix6d::Zero();
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d p = Eigen::Vector3d::Random() * 20, n = Eigen::Vector3d::Random().normalized();
    const Eigen::Vector3d x = T * p, ns = T.linear().transpose() * n;
    Eigen::Matrix<double, 6, 1> Jt, Js;
    Jt << n, x.cross(n);
    Js << ns, p.cross(ns);
    H_target += Jt * Jt.transpose();
    H_source += Js * Js.transpose();
  }
  const Matrix6d I = sourceFrameInformation(H_target, T);
  EXPECT_LT((I - H_source).norm(), 1e-9 * H_source.norm());
  EXPECT_GT((H_target - H_source).norm(), 0.1 * H_source.norm());  // the frames really differ here
}

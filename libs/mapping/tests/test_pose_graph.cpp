// PoseGraph: a ring of poses whose odometry has a heading bias is pulled back to the truth by one
// loop edge; the text graph reads back with MRPT's own loader.
#include <gtest/gtest.h>
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

PoseGraph ringWithDrift(const PoseVector& gt) {
  PoseGraph g;
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

TEST(PoseGraph, LoopEdgeRemovesHeadingDrift) {
  const auto gt = truth();
  PoseGraph g = ringWithDrift(gt);
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

TEST(PoseGraph, RemoveLastEdgeAndRestore) {
  const auto gt = truth();
  PoseGraph g = ringWithDrift(gt);
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

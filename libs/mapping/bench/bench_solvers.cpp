// The pose graph's two solvers side by side ([pose_graph] optimizer = lm | ceres), printed as tables;
// not a timed test. Run on one core (taskset -c 1); docs/benchmarks.md has the command and the table.
//
//   bench_mapping_solvers oracle
//     the tests' hilly ring (test_pose_graph.cpp: 400 keyframes, a ~1 km loop, heading and pitch
//     drift, 56 m off at the loop) with exact edges (the optimum is the truth) at three loop
//     informations, and with noisy edges (the truth within the noise): position error against the truth.
//   bench_mapping_solvers graph --run MAP_DIR --gt SIM/gt_trajectory.tum [--mount-x 0 --mount-z 1.9]
//     a map job's keyframe graph (MAP_DIR/posegraph.graph: odometry, loop edges) started from its
//     odometry alone (the chain of consecutive edges) and solved once by each solver; keyframe ATE
//     (rigid fit) against the simulator's truth at the keyframes' stamps (MAP_DIR/frames.csv).
//     The lidar in the truth's frame: (mount-x, 0, mount-z), the simulator's [lidar] mount (x 0, 1.9 m up).
#include <mrpt/graphs/CNetworkOfPoses.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/gnss_fusion/gnss_fusion.h"
#include "roadslam/mapping/pose_graph.h"

using namespace roadslam;
using namespace roadslam::mapping;

namespace {

std::string arg(int argc, char** argv, const std::string& name, const std::string& def = "") {
  for (int i = 2; i + 1 < argc; ++i)
    if (argv[i] == name) return argv[i + 1];
  if (def.empty()) throw std::runtime_error("missing " + name);
  return def;
}

struct Edge {
  size_t from, to;
  Eigen::Isometry3d Z;
  Matrix6d I;
};

struct Solved {
  PoseVector T;
  double ms = 0, final_error = 0;
  int iterations = 0;
};

/// One solve of the graph from \p init with \p o, its time added to \p s.ms / reps.
void solveOnce(const PoseVector& init, const std::vector<Edge>& edges, GraphOptimizer o, int reps, Solved& s) {
  PoseGraphParams p;
  p.optimizer = o;
  PoseGraph g(p);
  for (const auto& T : init) g.addNode(T);
  for (const auto& e : edges) g.addEdge(e.from, e.to, e.Z, e.I);
  const OptimizeStats st = g.optimize();
  s.ms += st.ms / reps;
  s.iterations = st.iterations;
  s.final_error = st.final_error;
  s.T = g.poses();
}

/// Both solvers on the same graph, \p reps times each, interleaved (the same load on the core for both).
std::pair<Solved, Solved> solveBoth(const PoseVector& init, const std::vector<Edge>& edges, int reps) {
  Solved lm, ce;
  for (int r = 0; r < reps; ++r) {
    solveOnce(init, edges, GraphOptimizer::Lm, reps, lm);
    solveOnce(init, edges, GraphOptimizer::Ceres, reps, ce);
  }
  return {lm, ce};
}

double maxError(const PoseVector& a, const PoseVector& b) {
  double e = 0;
  for (size_t i = 0; i < a.size(); ++i) e = std::max(e, (a[i].translation() - b[i].translation()).norm());
  return e;
}

/// rms position error after the best rigid fit of \p est to \p gt (Umeyama, no scale) [m].
double ate(const PoseVector& est, const std::vector<Eigen::Vector3d>& gt) {
  Eigen::Matrix3Xd A(3, est.size()), B(3, est.size());
  for (size_t i = 0; i < est.size(); ++i) {
    A.col(static_cast<Eigen::Index>(i)) = est[i].translation();
    B.col(static_cast<Eigen::Index>(i)) = gt[i];
  }
  const Eigen::Matrix4d T = Eigen::umeyama(A, B, false);
  const Eigen::Matrix3Xd R = (T.topLeftCorner<3, 3>() * A).colwise() + T.topRightCorner<3, 1>();
  return std::sqrt((R - B).colwise().squaredNorm().mean());
}

void header() {
  std::printf("| %-40s | solver | error [m] | final cost | iterations | ms per solve | error ratio ceres/lm | time ratio ceres/lm |\n"
              "|---|---|---|---|---|---|---|---|\n", "graph");
}

void rows(const std::string& name, const Solved& lm, const Solved& ce, double e_lm, double e_ce) {
  std::printf("| %-40s | lm     | %9.3g | %10.6g | %10d | %12.2f |  |  |\n", name.c_str(), e_lm, lm.final_error, lm.iterations, lm.ms);
  std::printf("| %-40s | ceres  | %9.3g | %10.6g | %10d | %12.2f | %.3g | %.2f |\n", name.c_str(), e_ce, ce.final_error,
              ce.iterations, ce.ms, e_lm > 0 ? e_ce / e_lm : 0.0, ce.ms / lm.ms);
}

PoseVector hillyTruth() {  // test_pose_graph.cpp's
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

int oracle() {
  const PoseVector gt = hillyTruth();
  const Eigen::Isometry3d bias(Eigen::AngleAxisd(0.001, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(0.0003, Eigen::Vector3d::UnitY()));
  Matrix6d I_odo = Matrix6d::Zero();
  I_odo.diagonal() << 1e4, 1e4, 1e4, 1e6, 1e6, 1e6;  // 1 cm, 1 mrad
  std::printf("pose-graph oracle: %zu keyframes on a 942 m hilly ring, odometry drifted 0.001 rad yaw + 0.0003 rad pitch per edge\n",
              gt.size());
  header();
  for (const bool noisy : {false, true}) {
    for (const double loop_scale : {1e4, 1e6, 1e8}) {
      std::mt19937_64 rng(7);
      std::normal_distribution<double> n01(0, 1);
      std::vector<Edge> edges;
      PoseVector init{gt[0]};
      for (size_t i = 1; i < gt.size(); ++i) {
        Eigen::Isometry3d d = gt[i - 1].inverse() * gt[i];
        if (noisy) {  // the edges' own noise: 1 cm, 1 mrad per axis
          Eigen::Isometry3d n = Eigen::Isometry3d::Identity();
          n.translation() = 0.01 * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
          const Eigen::Vector3d w = 0.001 * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
          n.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
          d = d * n;
        }
        init.push_back(init.back() * d * bias);
        edges.push_back({i - 1, i, d, I_odo});
      }
      Matrix6d I_loop = Matrix6d::Zero();
      I_loop.diagonal() << 1, 1, 1, 100, 100, 100;
      edges.push_back({gt.size() - 1, 0, gt.back().inverse() * gt[0], loop_scale * I_loop});
      const auto [lm, ce] = solveBoth(init, edges, 5);
      char name[80];
      std::snprintf(name, sizeof(name), "%s edges, loop information %.0e", noisy ? "noisy" : "exact", loop_scale);
      rows(name, lm, ce, maxError(lm.T, gt), maxError(ce.T, gt));
    }
  }
  std::printf("error: the largest keyframe position error against the truth; final cost: sum of squared Mahalanobis residuals\n");
  return 0;
}

Eigen::Isometry3d toEigen(const mrpt::poses::CPose3D& p) {
  const auto M = p.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = M(r, c);
  return T;
}

int graph(int argc, char** argv) {
  const std::string run = arg(argc, argv, "--run");
  const auto gt = datasets::readTum(arg(argc, argv, "--gt"));
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.translation() << std::stod(arg(argc, argv, "--mount-x", "0")), 0, std::stod(arg(argc, argv, "--mount-z", "1.9"));
  mrpt::graphs::CNetworkOfPoses3DInf g;
  g.loadFromTextFile(run + "/posegraph.graph");
  std::vector<Edge> edges;
  size_t loops = 0;
  for (const auto& [ft, pdf] : g.edges) {
    Edge e{ft.first, ft.second, toEigen(pdf.mean), Matrix6d::Zero()};
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) e.I(r, c) = pdf.cov_inv(r, c);
    if (e.to != e.from + 1) ++loops;
    edges.push_back(e);
  }
  // the odometry alone: the chain of consecutive edges from node 0
  const size_t N = g.nodes.size();
  PoseVector init(N, Eigen::Isometry3d::Identity()), job(N);
  for (size_t i = 0; i < N; ++i) job[i] = toEigen(g.nodes.at(i));
  init[0] = job[0];
  for (size_t i = 1; i < N; ++i) {
    init[i] = init[i - 1] * (job[i - 1].inverse() * job[i]);
    for (const auto& e : edges)
      if (e.from == i - 1 && e.to == i) init[i] = init[i - 1] * e.Z;
  }
  // the keyframes' stamps: frames.csv's keyframe = 1 rows, in order
  std::ifstream fc(run + "/frames.csv");
  std::string line;
  std::getline(fc, line);
  std::vector<double> stamps;
  while (std::getline(fc, line)) {
    std::stringstream ss(line);
    std::string f[6];
    for (auto& x : f) std::getline(ss, x, ',');
    if (f[5] == "1") stamps.push_back(std::stod(f[1]));
  }
  if (stamps.size() != N) throw std::runtime_error("frames.csv has " + std::to_string(stamps.size()) + " keyframes, the graph " + std::to_string(N));
  std::vector<Eigen::Vector3d> truth;
  for (const double t : stamps) truth.push_back((gnss_fusion::interpolatePose(gt.stamps_s, gt.poses, t) * mount).translation());
  std::printf("map job %s: %zu keyframes, %zu edges (%zu loop edges); keyframe ATE after a rigid fit to the truth: "
              "odometry %.3f m, the job's own (incremental) graph %.3f m\n",
              run.c_str(), N, edges.size(), loops, ate(init, truth), ate(job, truth));
  header();
  const auto [lm, ce] = solveBoth(init, edges, 5);
  rows("keyframe graph from its odometry", lm, ce, ate(lm.T, truth), ate(ce.T, truth));
  std::printf("error: keyframe ATE [m]; final cost: sum of squared Mahalanobis residuals; largest position difference "
              "between the two solutions %.2e m\n", maxError(lm.T, ce.T));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "oracle") return oracle();
    if (mode == "graph") return graph(argc, argv);
    std::fprintf(stderr, "usage: bench_mapping_solvers oracle | graph --run MAP_DIR --gt GT.tum [--mount-x M --mount-z M]\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_mapping_solvers: %s\n", e.what());
    return 1;
  }
}

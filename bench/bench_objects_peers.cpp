// Object clustering side by side with PCL's EuclideanClusterExtraction, same sweep, same
// candidate points: the ray-cast VLP-16 street of libs/objects' tests (8 cars and poles, ~12.7k
// points), ground labelled once (not timed). Ours: the whole segmentObjects (candidate filter,
// components, L-shape boxes) with each method, and with the tracker's update; PCL: a kd-tree on the
// candidates (x, y, z = 0: our criterion is the x-y distance) and EuclideanClusterExtraction with our
// distance (0.6 m) and minimum size (8). Built only with -DROADSLAM_BENCH_PEERS=ON.
#include <benchmark/benchmark.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include <cmath>

#include "../libs/objects/tests/synthetic_boxes.h"
#include "roadslam/objects/tracker.h"
#include "roadslam/preprocess/ground_segmentation.h"

using namespace roadslam;
using namespace roadslam::objects;

namespace {

using Sweep = test::LabelledSweep;
const Sweep& sweep() { return test::streetSweep(); }

/// The points segmentObjects clusters: non-ground, within the heights and the x-y range (its filter).
pcl::PointCloud<pcl::PointXYZ>::Ptr candidates(const Sweep& s, const ClusterParams& p) {
  auto c = pcl::PointCloud<pcl::PointXYZ>::Ptr(new pcl::PointCloud<pcl::PointXYZ>);
  for (size_t i = 0; i < s.scan.points.size(); ++i) {
    const ScanPoint& q = s.scan.points[i];
    if (s.g.ground[i]) continue;
    const double r = std::hypot(q.x, q.y);
    const float hg = s.g.height_above_ground_m[i];
    const double h = std::isfinite(hg) ? double(hg) : q.z + p.ground.sensor_height_m;
    if (r < p.min_range_m || r > p.max_range_m || h < p.min_height_m || h > p.max_height_m) continue;
    c->push_back(pcl::PointXYZ(q.x, q.y, 0.0f));
  }
  return c;
}

void BM_OursSegment(benchmark::State& st) {
  const auto& s = sweep();
  ClusterParams p;
  p.method = static_cast<ClusterMethod>(st.range(0));
  size_t n = 0;
  for (auto _ : st) n = segmentObjects(s.scan.points, true, s.g.ground, s.g.height_above_ground_m, p).size();
  st.counters["objects"] = static_cast<double>(n);
  st.SetLabel(toString(p.method));
}

void BM_OursSegmentAndTrack(benchmark::State& st) {
  const auto& s = sweep();
  ClusterParams p;
  Tracker tr;
  double t = 0;
  for (auto _ : st) {
    tr.update(t += 0.1, Eigen::Isometry3d::Identity(),
              segmentObjects(s.scan.points, true, s.g.ground, s.g.height_above_ground_m, p));
  }
  st.SetLabel("range_image + cv tracking");
}

void BM_PclEuclideanClusterExtraction(benchmark::State& st) {
  const auto& s = sweep();
  const ClusterParams p;
  const auto cloud = candidates(s, p);
  size_t n = 0;
  for (auto _ : st) {
    auto tree = pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>);
    tree->setInputCloud(cloud);
    std::vector<pcl::PointIndices> clusters;
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
    ec.setClusterTolerance(p.cluster_distance_m);
    ec.setMinClusterSize(p.min_points);
    ec.setMaxClusterSize(static_cast<int>(cloud->size()));
    ec.setSearchMethod(tree);
    ec.setInputCloud(cloud);
    ec.extract(clusters);
    n = clusters.size();
  }
  st.counters["clusters"] = static_cast<double>(n);
  st.counters["candidates"] = static_cast<double>(cloud->size());
  st.SetLabel("kd-tree + extraction, no boxes");
}

}  // namespace

// method: 0 range image, 1 Euclidean (x-y grid), 2 DBSCAN
BENCHMARK(BM_OursSegment)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OursSegmentAndTrack)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PclEuclideanClusterExtraction)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();

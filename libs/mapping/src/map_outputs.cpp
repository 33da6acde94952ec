#include "roadslam/mapping/map_outputs.h"

#include <chrono>
#include <future>
#include <tuple>

#include "roadslam/common/config.h"

namespace roadslam::mapping {

void MapOutputParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg) {
  point_map.loadFromConfigFile(cfg, "point_map");
  octomap.loadFromConfigFile(cfg, "octomap");
  grid.loadFromConfigFile(cfg, "grid");
}

void MapOutputParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  point_map.saveToConfigFile(cfg, "point_map");
  octomap.saveToConfigFile(cfg, "octomap");
  grid.saveToConfigFile(cfg, "grid");
}

MapOutputStats writeMaps(const std::string& dir, const Mapper& mapper, const PoseVector& trajectory,
                         const MapOutputParams& p) {
  const auto t0 = std::chrono::steady_clock::now();
  MapOutputStats st;
  const auto& kfs = mapper.keyframes();
  const PoseVector T_map_kf = mapper.keyframePoses();
  // the OctoMap (the slow one) on a worker thread while the other maps are written
  auto octo = std::async(std::launch::async, [&] {
    OctoMapBuilder b(p.octomap);
    size_t n = 0;
    double ms = 0, last_path = -1e18;
    for (size_t k = 0; p.octomap.enabled && k < kfs.size(); ++k) {
      if (kfs[k].path_m - last_path < p.octomap.keyframe_spacing_m) continue;
      last_path = kfs[k].path_m;
      ms += b.insert(kfs[k].points_lidar, T_map_kf[k]).ms;
      ++n;
    }
    b.writeBt(dir + "/map.bt");
    if (p.octomap.write_ot) b.writeOt(dir + "/map.ot");
    return std::make_tuple(n, b.numLeafs(), n ? ms / n : 0.0);
  });
  const auto points = buildPointMap(kfs, T_map_kf, p.point_map.voxel_m);
  st.points = points.size();
  writePly(dir + "/map.ply", points);
  writePcd(dir + "/map.pcd", points);
  const Grid2D grid = buildGrid(kfs, T_map_kf, p.grid);
  for (int8_t v : grid.cells) {
    if (v == 100) ++st.grid_occupied;
    if (v == 0) ++st.grid_free;
  }
  writeGridPng(dir + "/grid.png", dir + "/grid.yaml", grid);
  writeGridMrpt(dir + "/grid.gridmap", grid);
  writeSimpleMap(dir + "/keyframes.simplemap", kfs, T_map_kf);
  mapper.graph().saveToTextFile(dir + "/posegraph.graph");
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> loops;
  for (const auto& l : mapper.loopResults()) {
    if (l.accepted) loops.emplace_back(T_map_kf[l.query].translation(), T_map_kf[l.match].translation());
  }
  drawTopView(dir + "/map_top.png", points, trajectory, loops);
  std::tie(st.octomap_keyframes, st.octomap_leafs, st.octomap_ms_per_keyframe) = octo.get();
  st.ms_total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

}  // namespace roadslam::mapping

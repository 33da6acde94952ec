#include "roadslam/mapping/map_outputs.h"

#include <chrono>
#include <future>
#include <tuple>

#include "roadslam/common/config.h"
#include "roadslam/mapping/map_folder.h"

namespace roadslam::mapping {

void MapOutputParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg) {
  point_map.loadFromConfigFile(cfg, "point_map");
  octomap.loadFromConfigFile(cfg, "octomap");
  grid.loadFromConfigFile(cfg, "grid");
  seen_through.loadFromConfigFile(cfg, "seen_through");
}

void MapOutputParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const {
  point_map.saveToConfigFile(cfg, "point_map");
  octomap.saveToConfigFile(cfg, "octomap");
  grid.saveToConfigFile(cfg, "grid");
  seen_through.saveToConfigFile(cfg, "seen_through");
}

MapOutputStats writeMaps(const std::string& dir, const Mapper& mapper, const PoseVector& trajectory,
                         const MapOutputParams& p, OctoMapWorker* octomap, const std::vector<TopViewBox>& boxes) {
  const auto t0 = std::chrono::steady_clock::now();
  MapOutputStats st;
  const auto& kfs = mapper.keyframes();
  const PoseVector T_map_kf = mapper.keyframePoses();
  // the OctoMap (the slow one) on a worker thread while the other maps are written
  auto octo = std::async(std::launch::async, [&] {
    if (octomap) {  // built during the run: drain its queue
      const OctoMapBuilder& b = octomap->finish();
      b.writeBt(dir + "/map.bt");
      if (p.octomap.write_ot) b.writeOt(dir + "/map.ot");
      return std::make_tuple(octomap->inserted(), b.numLeafs(), octomap->meanInsertMs());
    }
    OctoMapBuilder b(p.octomap);
    double ms = 0;
    const auto items = p.octomap.enabled ? octoMapItems(kfs, T_map_kf, p.octomap.keyframe_spacing_m)
                                         : std::vector<OctoMapWorker::Item>{};
    for (const auto& it : items) ms += b.insert(it.points_lidar, it.T_map_lidar).ms;
    b.writeBt(dir + "/map.bt");
    if (p.octomap.write_ot) b.writeOt(dir + "/map.ot");
    return std::make_tuple(items.size(), b.numLeafs(), items.empty() ? 0.0 : ms / items.size());
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
  writeMapFolder(dir, kfs, T_map_kf, mapper.params().loop.place);
  mapper.graph().saveToTextFile(dir + "/posegraph.graph");
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> loops;
  for (const auto& l : mapper.loopResults()) {
    if (l.accepted) loops.emplace_back(T_map_kf[l.query].translation(), T_map_kf[l.match].translation());
  }
  drawTopView(dir + "/map_top.png", points, trajectory, loops, 1600, boxes);
  std::tie(st.octomap_keyframes, st.octomap_leafs, st.octomap_ms_per_keyframe) = octo.get();
  st.ms_total = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return st;
}

}  // namespace roadslam::mapping

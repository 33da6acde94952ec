#pragma once
/// \file map_outputs.h
/// Every map of a run, built from the keyframes at the optimised poses and written into a folder:
///   map.bt (OctoMap, max-likelihood; map.ot too when [octomap] write_ot), map.ply and map.pcd (point
///   map), grid.png + grid.yaml (map_server) and grid.gridmap (MRPT), keyframes.simplemap (MRPT),
///   posegraph.graph (MRPT text graph), map_top.png (top view with trajectory and loops), map.json +
///   keyframes.bin (the folder's version, keyframes with points and Scan Context: map_folder.h).
/// The OctoMap is built on a worker thread while the other maps are written.

#include <string>

#include "roadslam/mapping/mapper.h"
#include "roadslam/mapping/maps.h"
#include "roadslam/mapping/octo_map.h"
#include "roadslam/mapping/octo_worker.h"
#include "roadslam/mapping/seen_through.h"

namespace roadslam::mapping {

/// Ini sections [point_map], [octomap], [grid], [seen_through].
struct MapOutputParams {
  PointMapParams point_map;
  OctoMapParams octomap;
  GridParams grid;
  SeenThroughParams seen_through;  ///< the pass the caller runs on the keyframes before writeMaps

  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const;
};

struct MapOutputStats {
  size_t points = 0;               ///< point map size [-]
  size_t octomap_keyframes = 0;    ///< keyframes inserted into the OctoMap [-]
  size_t octomap_leafs = 0;        ///< [-]
  double octomap_ms_per_keyframe = 0;  ///< mean insertion time [ms]
  size_t grid_occupied = 0, grid_free = 0;  ///< cells [-]
  double ms_total = 0;             ///< wall time of writeMaps [ms]
};

/// Writes the files listed above into \p dir for \p mapper's keyframes at its optimised poses;
/// \p trajectory (T_map_lidar of every frame) is drawn in the top view. The OctoMap is \p octomap's
/// (built during the run) when given, else built here; \p boxes (moving tracks) are drawn in the top
/// view. Throws naming the file.
MapOutputStats writeMaps(const std::string& dir, const Mapper& mapper, const PoseVector& trajectory,
                         const MapOutputParams& p, OctoMapWorker* octomap = nullptr,
                         const std::vector<TopViewBox>& boxes = {});

}  // namespace roadslam::mapping

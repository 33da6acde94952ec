#include <octomap/OcTree.h>

#include <fstream>
#include <stdexcept>

#include "roadslam/eval/mot_metrics.h"

namespace roadslam::eval {

GhostCount countGhostVoxels(const std::string& gt_objects_json, const std::string& gt_trajectory_tum,
                            const std::string& run_trajectory_tum, const std::string& map_bt, double margin_m,
                            double max_range_m, bool seen_only) {
  if (!std::ifstream(map_bt)) throw std::runtime_error("cannot read '" + map_bt + "'");
  octomap::OcTree tree(0.1);
  if (!tree.readBinary(map_bt)) throw std::runtime_error("'" + map_bt + "' is no binary OctoMap");
  std::vector<Eigen::Vector3f> centres;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    if (tree.isNodeOccupied(*it)) centres.emplace_back(it.getX(), it.getY(), it.getZ());
  }
  return countGhostsAmong(gt_objects_json, gt_trajectory_tum, run_trajectory_tum, centres, margin_m, max_range_m, seen_only);
}

}  // namespace roadslam::eval

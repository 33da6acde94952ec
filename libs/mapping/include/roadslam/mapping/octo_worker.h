#pragma once
/// \file octo_worker.h
/// The run's OctoMap, updated per keyframe on a worker thread so the odometry never waits for it:
/// push() queues a keyframe (points in its lidar frame, pose T_map_lidar) and returns at once;
/// after a loop closure rebuild() drops the queue and the map and re-queues every keyframe at its
/// corrected pose; finish() drains the queue and hands the map over.

#include <Eigen/Geometry>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "roadslam/mapping/loop_closure.h"
#include "roadslam/mapping/octo_map.h"

namespace roadslam::mapping {

class OctoMapWorker {
 public:
  struct Item {
    std::vector<Eigen::Vector3f> points_lidar;  ///< lidar frame [m]
    Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  };

  explicit OctoMapWorker(OctoMapParams params);
  ~OctoMapWorker();  ///< stops the thread (pending items are dropped)
  OctoMapWorker(const OctoMapWorker&) = delete;
  OctoMapWorker& operator=(const OctoMapWorker&) = delete;

  void push(Item item);
  /// Clears the map and queues \p all (the keyframes at their corrected poses) instead of the queue.
  void rebuild(std::vector<Item> all);
  /// Waits until every queued item is inserted, stops the thread and returns the map.
  const OctoMapBuilder& finish();

  size_t inserted() const;        ///< keyframes inserted since the last rebuild [-]
  size_t rebuilds() const;        ///< [-]
  double meanInsertMs() const;    ///< mean insertion time over all insertions [ms]

 private:
  void run();

  OctoMapBuilder builder_;
  mutable std::mutex m_;
  std::condition_variable cv_, idle_cv_;
  std::deque<Item> queue_;
  bool clear_ = false, stop_ = false, busy_ = false;
  size_t inserted_ = 0, rebuilds_ = 0, total_inserts_ = 0;
  double total_ms_ = 0;
  std::thread thread_;
};

/// Keyframe \p k goes into the OctoMap when it is the first one past a multiple of \p spacing_m of
/// path (keyframe 0 always): the choice depends on the path only, so a rebuild takes the same ones.
bool takesOctoMap(const std::vector<Keyframe>& kfs, size_t k, double spacing_m);
/// The keyframes takesOctoMap() selects, at the poses \p T_map_kf.
std::vector<OctoMapWorker::Item> octoMapItems(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf,
                                              double spacing_m);

}  // namespace roadslam::mapping

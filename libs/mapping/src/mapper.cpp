#include "roadslam/mapping/mapper.h"

#include <unordered_set>

#include "roadslam/common/voxel_hash.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "ini_keys.h"

namespace roadslam::mapping {
namespace {

std::vector<Eigen::Vector3f> downsample(const std::vector<Eigen::Vector3d>& pts, double voxel_m) {
  std::unordered_set<Eigen::Vector3i, VoxelKeyHash> seen;
  std::vector<Eigen::Vector3f> out;
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    if (seen.insert((p / voxel_m).array().floor().cast<int>().matrix()).second) out.push_back(p.cast<float>());
  }
  return out;
}

}  // namespace

void MapperParams::fields(ParamTable& t) {
  t.num("keyframe_voxel_m", keyframe_voxel_m);
}

void MapperParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<MapperParams>());
  if (keyframe_voxel_m <= 0) throw std::runtime_error("[" + s + "] keyframe_voxel_m must be > 0");
  graph.loadFromConfigFile(cfg, "pose_graph");
  loop.loadFromConfigFile(cfg, "loop_closure");
}

void MapperParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
  graph.saveToConfigFile(cfg, "pose_graph");
  loop.saveToConfigFile(cfg, "loop_closure");
}

Mapper::Mapper(MapperParams params) : p_(std::move(params)), graph_(p_.graph), places_(p_.loop.place) {}

size_t Mapper::acceptedLoops() const {
  size_t n = 0;
  for (const auto& l : loops_) n += l.accepted ? 1 : 0;
  return n;
}

void Mapper::chainWheel(const std::optional<WheelMotion>& wheel) {
  if (!wheel) {
    wheel_complete_ = false;
    return;
  }
  T_kfbase_base_ = T_kfbase_base_ * wheel->T_baseprev_basecurr;
  T_base_lidar_ = wheel->T_base_lidar;
  wheel_path_m_ += wheel->T_baseprev_basecurr.translation().norm();
}

bool Mapper::addFrame(const odometry::FrameResult& f, const std::vector<Eigen::Vector3d>& points_lidar,
                      const std::optional<WheelMotion>& wheel) {
  if (p_.graph.can_edges) chainWheel(wheel);
  if (f.status == odometry::FrameStatus::Skipped) return false;
  if (have_last_) path_m_ += (f.T_world_lidar.translation() - T_odom_last_.translation()).norm();
  T_odom_last_ = f.T_world_lidar;
  have_last_ = true;
  if (f.keyframe || kfs_.empty()) {
    addKeyframe(f, points_lidar);
  }
  if (frame_kf_.size() <= f.index) frame_kf_.resize(f.index + 1, -1);
  frame_kf_[f.index] = static_cast<long>(kfs_.size()) - 1;
  if (!(f.keyframe || kfs_.size() == 1) || !p_.loop.enabled) return false;
  return detectLoop();
}

void Mapper::addKeyframe(const odometry::FrameResult& f, const std::vector<Eigen::Vector3d>& points_lidar) {
  Keyframe kf;
  kf.frame_index = f.index;
  kf.stamp_s = f.stamp_s;
  kf.T_odom_lidar = f.T_world_lidar;
  kf.path_m = path_m_;
  kf.points_lidar = downsample(points_lidar, p_.keyframe_voxel_m);
  if (p_.loop.candidates != LoopCandidates::Radius) {
    kf.descriptor = place::makeScanContext(points_lidar, p_.loop.place);
    places_.add(kfs_.size(), path_m_, kf.descriptor);
  }
  if (kfs_.empty()) {
    graph_.addNode(f.T_world_lidar);
  } else {
    const size_t prev = kfs_.size() - 1;
    Eigen::Isometry3d T_prev_cur = kfs_[prev].T_odom_lidar.inverse() * f.T_world_lidar;
    // the odometry's information is about its map frame (left perturbations, lever arms from the map's
    // origin); the edge's residual is in this keyframe's lidar frame
    Matrix6d info = graph_.odometryInformation(sourceFrameInformation(f.information, f.T_world_lidar));
    if (p_.graph.can_edges && wheel_complete_) {
      // T_lidarkf_lidar = T_base_lidar^-1 * T_basekf_base * T_base_lidar
      const Eigen::Isometry3d T_can = T_base_lidar_.inverse() * T_kfbase_base_ * T_base_lidar_;
      const Matrix6d info_can = graph_.canInformation(wheel_path_m_, T_base_lidar_);
      T_prev_cur = fuseMeasurements(T_prev_cur, info, T_can, info_can);
      info += info_can;
      ++can_edges_;
    }
    const size_t id = graph_.addNode(graph_.pose(prev) * T_prev_cur);
    graph_.addEdge(prev, id, T_prev_cur, info);
  }
  T_kfbase_base_ = Eigen::Isometry3d::Identity();
  wheel_path_m_ = 0;
  wheel_complete_ = true;
  kfs_.push_back(std::move(kf));
}

bool Mapper::detectLoop() {
  const auto& lp = p_.loop;
  if (path_m_ - last_query_path_m_ < lp.check_every_m || path_m_ - last_loop_path_m_ < lp.skip_after_loop_m) {
    return false;
  }
  last_query_path_m_ = path_m_;
  const size_t query = kfs_.size() - 1;
  const PoseVector T_map_kf = graph_.poses();
  if (lp.candidates != LoopCandidates::ScanContext) {
    for (size_t match : findLoopCandidates(kfs_, T_map_kf, query, lp)) {
      if (tryLoop(verifyLoop(kfs_, T_map_kf, query, match, lp))) return true;
    }
  }
  if (lp.candidates != LoopCandidates::Radius) {
    for (size_t match : findPlaceCandidates(places_, kfs_, query, lp)) {
      if (tryLoop(verifyPlaceLoop(kfs_, T_map_kf, query, match, lp, features_))) return true;
    }
  }
  return false;
}

bool Mapper::tryLoop(LoopResult r) {
  if (!r.accepted) {
    loops_.push_back(std::move(r));
    return false;
  }
  // graph-level consistency: a loop the optimised graph cannot satisfy contradicts the odometry
  const PoseVector before = graph_.poses();
  graph_.addEdge(r.match, r.query, r.T_match_query, r.information);
  graph_.optimize();
  const Eigen::Isometry3d T_est = graph_.pose(r.match).inverse() * graph_.pose(r.query);
  const double residual_m = (r.T_match_query.inverse() * T_est).translation().norm();
  if (residual_m > p_.loop.max_loop_residual_m) {
    graph_.removeLastEdge();
    graph_.setPoses(before);
    r.accepted = false;
    r.reason = "graph residual";
    loops_.push_back(std::move(r));
    return false;
  }
  last_loop_path_m_ = path_m_;
  loops_.push_back(std::move(r));
  return true;
}

Eigen::Isometry3d Mapper::correctedPose(const odometry::FrameResult& f, const PoseVector& T_map_kf) const {
  if (f.index >= frame_kf_.size() || frame_kf_[f.index] < 0) return f.T_world_lidar;
  const auto k = static_cast<size_t>(frame_kf_[f.index]);
  return T_map_kf[k] * kfs_[k].T_odom_lidar.inverse() * f.T_world_lidar;
}

}  // namespace roadslam::mapping

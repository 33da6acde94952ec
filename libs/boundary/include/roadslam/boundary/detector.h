#pragma once
/// \file detector.h
/// Road boundaries, obstacles and free space from a deskewed sweep and its pose.
/// Per sweep: ground labels with heights (libs/preprocess, slope-following line fits) -> curb points
/// along each ring (a 0.05-0.30 m jump between two flat pieces, nothing tall in the same cell) ->
/// obstacle points (0.3-3 m above ground) clustered by the objects segmentation (objects::segmentObjects,
/// the one clustering of the chain), each with a convex hull and its L-shape box -> free space by polar ray casting up to the first curb or obstacle -> left/right
/// boundary: RANSAC polynomial over the curb evidence of many sweeps (a CurbMap in the map frame,
/// aged out behind the vehicle, moved into the current vehicle frame and then into the arc frame of
/// the path driven over the last path_curvature_frames sweeps, so fits follow corners), scored by
/// the distance bins it covers, gaps between curb stretches bridged up to max_bridge_m; a side whose
/// own cells end early continues parallel to the other side at the road's width (measured where
/// both were fitted); a side not seen (or jumping away from its track) is held from the previous
/// sweeps, moved with the vehicle, for max_hold_frames, and says so in its reason.

#include <array>
#include <deque>
#include <random>
#include <unordered_set>
#include <vector>

#include "roadslam/boundary/curb_map.h"
#include "roadslam/boundary/params.h"
#include "roadslam/boundary/types.h"
#include "roadslam/common/scan.h"

namespace roadslam::boundary {
namespace detail {
struct BendFrame;
}

/// Class of every point of \p scan (lidar frame, sensor at the origin), same order, plus the curb
/// points' positions. Exposed for tests and drawing.
struct Labelling {
  std::vector<PointClass> cls;
  std::vector<float> height_m;          ///< height above the local ground [m], NaN when unknown
  size_t ground = 0, curb = 0, obstacle = 0;
};
Labelling labelPoints(const Scan& scan, const Params& p);

class BoundaryDetector {
 public:
  explicit BoundaryDetector(Params p);
  /// \p scan deskewed, in the lidar frame at the pose \p T_map_lidar (time \p stamp_s).
  /// \p local_map_map: optional points of the local map around the vehicle (accumulated recent
  /// sweeps, e.g. the mapping module's) in the map frame [m]; they join the ground and curb
  /// labelling (curbs seen from many sweeps), while obstacles and free space stay with the current
  /// sweep (a map smears moving cars, and its points are not rays from the sensor).
  /// Never throws on data: problems come back in BoundaryFrame::status and the sides' reasons.
  BoundaryFrame process(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double stamp_s,
                        const std::vector<Eigen::Vector3f>* local_map_map = nullptr);
  const Params& params() const { return p_; }
  /// The accumulated curb evidence (map frame).
  const CurbMap& curbMap() const { return curb_map_; }
  /// Whole-drive mode, first pass (the drive's sweeps in order, each with its pose and stamp): adds
  /// the curb points of \p scan to the curb map, which this mode never prunes, and the pose to the
  /// drive's path.
  void accumulate(const Scan& scan, const Eigen::Isometry3d& T_map_lidar, double stamp_s);
  /// Ends the first pass. From then on process() leaves the curb map as it is and fits each sweep
  /// from the cells of the whole drive near it (seen by whole_drive_min_sightings sweeps), in the
  /// frame of the drive's own path (PathFrame: s along the path, d to its left). Curbs that parked
  /// cars hide from the vehicle ahead were seen from elsewhere on the drive: through gaps, when
  /// passing, from behind. Needs poses consistent over the drive (a trajectory, or a pose graph's).
  void finishAccumulation();
  bool wholeDrive() const { return whole_drive_; }
  /// The curb-map cells the fit of a sweep at \p T_map_lidar uses, vehicle frame [m]: those seen by
  /// curb_min_sightings sweeps (whole-drive mode: whole_drive_min_sightings, within the fit's reach).
  std::vector<Vec2> fitCells(const Eigen::Isometry3d& T_map_lidar) const;
  /// The labelling of the last processed sweep (its points first, then any local-map points).
  const Labelling& lastLabelling() const { return last_; }

 private:
  Params p_;
  size_t frames_ = 0;
  CurbMap curb_map_;  ///< curb evidence of past sweeps, map frame
  bool whole_drive_ = false;               ///< see finishAccumulation()
  std::vector<double> drive_stamps_s_;     ///< whole-drive mode: the accumulated sweeps' stamps [s] ...
  std::vector<Eigen::Vector3d> drive_pos_; ///< ... and positions, map frame [m]
  std::vector<Eigen::Vector3d> drive_tall_;///< ... and tall points (curb_veto_cells), map frame [m], one per cell
  std::unordered_set<int64_t> drive_tall_cells_;  ///< the cells of drive_tall_
  Labelling last_;
  /// Per side (0 left, 1 right): the last accepted boundary, map frame, and sweeps held since.
  struct Track {
    std::vector<Eigen::Vector3d> map_pts;
    double confidence = 0;
    double yaw_map = 0;  ///< vehicle heading when the track was last fitted, map frame [rad]
    int held = 0;
    bool valid = false;
  };
  std::array<Track, 2> tracks_;
  std::deque<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> path_;  ///< last poses T_map_lidar
  double pathCurvature(const Eigen::Isometry3d& T_map_lidar);
  /// Left/right of \p f from the curb map (arc frame fits, parallel continuation, tracking).
  void fitSides(const Eigen::Isometry3d& T_map_lidar, std::mt19937& rng, BoundaryFrame& f);
  double road_width_m_ = 0;      ///< curb to curb where both sides had their own fit; 0 = not measured [m]
  size_t road_width_frame_ = 0;  ///< sweep of the last measurement
  double new_width_m_ = 0;       ///< a width off road_width_m_ by more than width_jump_m, measured ...
  int new_width_count_ = 0;      ///< ... this many times in a row [-]
  /// Road width from a measured curb-to-curb \p w (NaN: none); \p known: road_width_m_ is current.
  void updateWidth(double w, bool known, size_t frame);
  /// Points of track \p tr in the fit frame \p arc; \p stale: also of a track no longer held (its last line).
  std::vector<Vec2> heldPoints(const Track& tr, const Eigen::Isometry3d& T_map_lidar, const detail::BendFrame& arc,
                               bool stale = false) const;
  /// Both sides fitted but curb to curb differs from the road's width by more than width_jump_m: the
  /// side that left its track (a line beyond the sidewalk while parked cars hide the curb ahead) is
  /// refitted on the cells near the other side moved by the road's width, or becomes unknown.
  void checkWidth(SideBoundary& l, SideBoundary& r, const std::vector<Vec2>& pts, std::mt19937& rng,
                  const Eigen::Isometry3d& T_map_lidar, const detail::BendFrame& arc) const;
  /// \p fresh and \p pts in the fit frame \p frame (see BendFrame in src/internal.h).
  SideBoundary track(SideBoundary fresh, const std::vector<Vec2>& pts, int side, std::mt19937& rng, Track& tr,
                     const Eigen::Isometry3d& T_map_lidar, const detail::BendFrame& frame) const;
};

}  // namespace roadslam::boundary

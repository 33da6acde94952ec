#pragma once
/// \file odometry.h
/// LiDAR odometry: scan-to-local-map registration with constant-velocity (or external) motion
/// prediction, deskewing, an adaptive correspondence threshold, keyframes and standstill handling.
/// Per frame (KISS-ICP's pipeline, Vizzo et al. 2023, with a motion prior and degeneracy handling):
///   preprocess -> deskew with the predicted motion -> voxelize -> register against the local map
///   -> (prior along degenerate directions) -> standstill check -> update the local map.
/// Frames: "world" is the odometry frame = lidar frame of the first sweep; poses are T_world_lidar at
/// FrameResult::stamp_s: the sweep's stamp (first firing) plus deskew_reference * sweep_duration_s
/// for sweeps with point times (mid-sweep by default), the sweep stamp otherwise.

#include <cmath>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/common/oriented_box.h"
#include "roadslam/common/scan.h"
#include "roadslam/odometry/scan_matcher.h"
#include "roadslam/odometry/vertical_structures.h"
#include "roadslam/preprocess/chain.h"
#include "roadslam/registration/adaptive_threshold.h"
#include "roadslam/registration/gaussian_voxel_map.h"
#include "roadslam/registration/registration.h"

namespace mrpt::config {
class CConfigFileBase;
}
namespace roadslam {
class ParamTable;
}

namespace roadslam::odometry {

/// The scan matcher the odometry composes (ini [odometry] matcher; scan_matcher.h, one class each).
enum class Matcher {
  VoxelMap,     ///< `voxel_map`: the incremental Gaussian voxel map (registration/gaussian_voxel_map.h)
  Registration  ///< `registration`: the [registration] method (ICP/NDT) against a registration::Target
};
std::string toString(Matcher m);
/// The Matcher of an ini value; throws std::invalid_argument naming the valid ones.
Matcher matcherFromString(const std::string& s);

/// What matcher = registration aligns each sweep to.
enum class RegistrationTarget {
  LocalMap,  ///< `local_map`: the map of recent frames
  LastScan   ///< `last_scan`: the previous sweep alone, as the MATLAB thesis matched consecutive sweeps
};
std::string toString(RegistrationTarget t);
/// The RegistrationTarget of an ini value; throws std::invalid_argument naming the valid ones.
RegistrationTarget registrationTargetFromString(const std::string& s);

/// Odometry parameters. Ini section [odometry]; the preprocessing chain and the registration read
/// their own sections ([preprocess], [registration]).
struct Params {
  /// Scan matcher. `voxel_map`: the incremental Gaussian voxel map (fast, default);
  /// `registration`: the [registration] method (ICP/NDT) against a target rebuilt from the local map
  /// points whenever the map changes (slow: for comparisons and the thesis configs).
  Matcher matcher = Matcher::VoxelMap;
  /// With matcher = registration: `local_map` (the map of recent frames) or `last_scan` (scan to
  /// scan, as the MATLAB thesis matched consecutive sweeps).
  RegistrationTarget registration_target = RegistrationTarget::LocalMap;
  double registration_voxel_m = 0.75;   ///< voxel of the source points registered [m]
  double map_voxel_m = 1.0;            ///< voxel of the local map [m]
  int map_points_per_voxel = 20;       ///< points kept per map voxel [-]
  /// voxel_map: a map voxel off the road crossed by one scan ring constrains across the vertical
  /// surface through it (registration/src/gaussian_voxel_map.cpp); false = it waits for a second ring [-]
  bool map_ring_lines_on_walls = true;
  double map_insert_voxel_m = 0.25;    ///< each frame adds one point per voxel of this size to the map [m]
  double map_radius_m = 80.0;          ///< local map radius around the vehicle [m]
  bool adaptive_threshold = true;      ///< KISS-ICP adaptive max correspondence distance
  double initial_threshold_m = 2.0;    ///< threshold before the adaptive one has data [m]
  /// Upper bound of the adaptive sigma [m]: a few bad frames at the start (an empty map, a car that
  /// is already moving) must not widen the kernel until nothing is an outlier any more.
  double max_threshold_m = 10.0;
  /// Lower bound of the adaptive sigma [m]: with a good motion prior (wheel odometry) the model
  /// deviation shrinks to millimetres, and pairs within 3 sigma would then be none at all; at 0.1 m
  /// (kernel 3 cm) the odometry without the gravity prior lost the urban loop's first corner.
  double min_threshold_m = 0.2;
  double min_motion_m = 0.1;           ///< motions below this do not feed the adaptive threshold [m]
  double max_range_m = 100.0;          ///< sensor range for the adaptive threshold [m]
  bool deskew = true;                  ///< motion-compensate sweeps that carry point times
  double deskew_reference = 0.5;       ///< pose time within the sweep when deskewing [fraction of the sweep]
  /// A sweep that arrives without point times gets them from the azimuth (clockwise, cut behind,
  /// its stamp the first firing: sweep_timing.h), so it is deskewed too. KITTI folders are timed by
  /// their source ([kitti], which knows its stamps are mid-sweep) before they reach the odometry.
  bool times_from_azimuth = true;
  double sweep_duration_s = 0.1;       ///< nominal sweep period, used when stamps are missing [s]
  /// A drive that starts at speed: the second sweep's motion, still unknown to constant velocity, is
  /// first found by a wide multi-resolution NDT against the first sweep (2, 4, 8 m cells, up to 15 m),
  /// and the first sweep is then deskewed with it before the map holds it [-]
  bool first_motion_search = true;
  double keyframe_distance_m = 1.0;    ///< new keyframe after this translation [m]
  double keyframe_angle_rad = 10.0 * M_PI / 180.0;  ///< ... or this rotation [rad]; ini keyframe_angle_deg
  double standstill_translation_m = 0.02;  ///< motion below this and ... [m/frame]
  double standstill_rotation_rad = 0.1 * M_PI / 180.0; ///< ... below this is standing [rad/frame]; ini _deg
  double standstill_speed_mps = 0.05;  ///< a prior speed below this is standing [m/s]
  /// Replace the registration's weak eigen-directions (degeneracy_threshold) by an external motion
  /// prior (wheel odometry). The constant-velocity prediction is not used there: it carries no
  /// information of its own and measured worse. (A weak motion, motion_degeneracy_threshold, takes
  /// the prediction in any case: the prior, else constant velocity.)
  bool use_prior_on_degeneracy = true;
  double degeneracy_threshold = 0.01;  ///< normalised Hessian eigenvalue below which a direction is weak [-]
  /// voxel_map: a frame is degenerate when the scans' information of the translation along the
  /// predicted motion, n^T H_tt n per pair without single-ring voxels (registration::SurfaceInformation::along),
  /// is below this: the fraction of the pairs that measure the motion (a tunnel) [-]. 0 = off.
  double motion_degeneracy_threshold = 0.01;
  /// ... and only once a frame's scans clearly saw the motion (this much information along it, after
  /// a start or a standstill): constant velocity then repeats a measured motion, not noise [-]
  double motion_seen_threshold = 0.03;
  /// A registration that used up its iterations is still taken when at least this fraction of the
  /// source points found a partner (IRLS often ends in a tiny limit cycle, not in a bad pose) [-]
  double min_inlier_fraction = 0.3;
  /// Label the road in every sweep (line-fit ground segmentation, [preprocess] seg_* keys) so map
  /// voxels crossed by a single ring of road still constrain height (16-beam sensors) [-]
  bool ground_aware_map = true;
  double map_ground_max_range_m = 0.0;   ///< road points farther than this stay out of the map (0 = all) [m]
  /// Tilt prior from vertical structures (walls, poles, trunks: vertical_structures.h) in the voxel-map
  /// matcher, against the up direction summed over all frames so far (robustly).
  bool gravity_prior = true;
  double gravity_weight_m2 = 1.0;       ///< registration::GravityPrior::scale_m2 [m^2]
  double gravity_kernel_rad = 2.0 * M_PI / 180.0;    ///< [rad]; ini gravity_kernel_deg
  /// The prior starts once the summed structures know both tilts this well [1/rad^2]
  double gravity_min_information = 1e5;
  VerticalStructureParams vertical;     ///< ini vertical_* keys

  preprocess::PreprocessParams preprocess;
  registration::Params registration;

  /// The [odometry] keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Reads [odometry] keys from \p section plus the [preprocess] and [registration] sections.
  /// Throws naming section/key on malformed values.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "odometry",
                          const std::string& preprocess_section = "preprocess",
                          const std::string& registration_section = "registration");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "odometry",
                        const std::string& preprocess_section = "preprocess",
                        const std::string& registration_section = "registration") const;
};

/// Motion between the previous and the current sweep from another sensor (wheel odometry).
struct MotionPrior {
  Eigen::Isometry3d T_prev_curr = Eigen::Isometry3d::Identity();  ///< lidar motion, prev to current frame
  double speed_mps = 0;                                           ///< vehicle speed [m/s]
};

/// A region whose points stay out of the odometry's local map: a moving object a later stage found
/// (the pipeline hands the objects stage's moving tracks back; the odometry knows nothing of objects).
/// A box in the world frame moving at constant velocity in x-y.
struct MapExclusion {
  double stamp_s = 0;                                           ///< time of box [s]
  OrientedBox box;                                              ///< at stamp_s, world frame, margins included [m, rad]
  Eigen::Vector2d velocity_world_mps = Eigen::Vector2d::Zero(); ///< [m/s]
  /// setMapExclusions() also erases the local-map voxels whose mean the box held over this long
  /// before stamp_s (the points the object left before it was labelled moving); 0: none [s]
  double erase_back_s = 0;
  /// Whether \p p_world lies inside the box moved to time \p t_s.
  bool contains(const Eigen::Vector3d& p_world, double t_s) const;
};

enum class FrameStatus {
  Ok,             ///< registered and converged
  First,          ///< first frame: defines the world frame
  Standstill,     ///< vehicle standing: pose held, map not updated
  /// converged, but the scans leave a direction unmeasured (degeneracy_threshold, or
  /// motion_degeneracy_threshold along the motion): it comes from the external motion prior, or from
  /// the constant-velocity prediction without one; FrameResult::information is reduced there
  Degenerate,
  NotConverged,   ///< registration failed: pose from the prediction (reason in FrameResult::reason)
  Skipped,        ///< dropped by frame skipping (no pose)
  Empty           ///< no usable points: pose from the prediction
};
const char* toString(FrameStatus s);

/// What the odometry did with one frame.
struct FrameResult {
  size_t index = 0;             ///< 0-based frame counter
  double stamp_s = 0;           ///< time of T_world_lidar [s] (see the file comment)
  Eigen::Isometry3d T_world_lidar = Eigen::Isometry3d::Identity();
  FrameStatus status = FrameStatus::Ok;
  std::string reason;           ///< registration status text when not Ok; an ignored prior
  bool keyframe = false;
  const char* point_times = "none";  ///< how the sweep was timed: sensor, azimuth or none
  bool deskewed = false;        ///< motion-compensated (deskew on and the sweep had point times)
  int points_in = 0, points_registered = 0;  ///< raw and registered source points [-]
  int iterations = 0, inliers = 0;
  double fitness_m = 0;         ///< inlier RMSE [m]
  double threshold_m = 0;       ///< correspondence threshold used [m]
  int weak_directions = 0;      ///< degenerate directions of the registration [-]
  double min_eigenvalue = 0;    ///< smallest normalised Hessian eigenvalue (degeneracy measure) [-]
  /// information of the translation along the predicted motion per pair, single-ring voxels left out
  /// (registration::SurfaceInformation::along); NaN when the motion is too small to have a direction [-]
  double motion_information = std::nan("");
  int vertical_constraints = 0; ///< tilt constraints from vertical structures (gravity prior) [-]
  int map_points_excluded = 0;  ///< points kept out of the local map by setMapExclusions() [-]
  double ms_preprocess = 0, ms_register = 0, ms_map = 0, ms_total = 0;  ///< wall time [ms]
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
};

class Odometry {
 public:
  explicit Odometry(Params params);
  ~Odometry();

  /// Processes one sweep (lidar frame). Never throws on data problems: they come back as a status.
  /// A prior that is not finite is ignored (constant velocity instead), and FrameResult::reason says so.
  FrameResult process(Scan scan, const std::optional<MotionPrior>& prior = std::nullopt);

  const Params& params() const { return params_; }
  /// Time the pose of \p scan will refer to (FrameResult::stamp_s) [s]: for asking a motion prior
  /// for the interval before calling process(). A sweep with point times spans sweep_duration_s from
  /// its stamp (the first firing), and its pose is that at deskew_reference of it, deskewed or not.
  double poseTimeOf(const Scan& scan) const {
    const bool times = scan.has_point_times || params_.times_from_azimuth;
    return scan.stamp_s + (times ? params_.deskew_reference * params_.sweep_duration_s : 0.0);
  }
  /// Points inside \p boxes (each moved to the frame's pose time) stay out of the local-map updates
  /// of the frames processed after this call, until the next call replaces them (empty: none).
  /// Boxes with erase_back_s > 0 also erase the voxels of the local map they swept over that time
  /// (voxel_map matcher; the other matchers' maps keep them); returns how many voxels went.
  size_t setMapExclusions(std::vector<MapExclusion> boxes);
  /// The scan matcher (Params::matcher) and its local map.
  const ScanMatcher& matcher() const { return *matcher_; }
  /// Deskewed, preprocessed points of the last frame (lidar frame) [m] (for keyframe maps).
  const std::vector<Eigen::Vector3d>& lastFramePoints() const { return frame_.points; }
  const preprocess::PreprocessTotals& preprocessTotals() const { return chain_.totals(); }

 private:
  Eigen::Isometry3d predict(const std::optional<MotionPrior>& prior) const;
  /// The tilt prior from vertical structures: on (Params::gravity_prior) and taken by the matcher.
  bool usesGravityPrior() const { return params_.gravity_prior && matcher_->takesGravityPrior(); }
  void applyPriorOnWeakDirections(const Eigen::Matrix<double, 6, Eigen::Dynamic>& weak, double lever_m,
                                  const Eigen::Isometry3d& T_pred, Eigen::Isometry3d& T_est, bool about_sensor) const;
  /// Marks \p res degenerate and puts the prediction into \p T_est along the directions the scans
  /// leave unmeasured (weak_directions.h), reducing res.information there.
  void judgeDegeneracy(const registration::RegistrationResult& r, const registration::SurfaceInformation& surface,
                       const Eigen::Isometry3d& T_pred, const std::optional<MotionPrior>& prior,
                       Eigen::Isometry3d& T_est, FrameResult& res) const;
  bool isStandstill(const Eigen::Isometry3d& delta, const std::optional<MotionPrior>& prior) const;
  void updateKeyframe(FrameResult& res);
  void updateUp(const FrameResult& res);
  registration::RegistrationResult match(const std::vector<Eigen::Vector3d>& source,
                                         const Eigen::Isometry3d& T_pred, FrameResult& res,
                                         registration::SurfaceInformation* surface = nullptr);
  /// Adds the frame's points at \p T_world_lidar (time \p stamp_s) to the local map; returns how many
  /// the exclusions kept out.
  int updateMap(const Eigen::Isometry3d& T_world_lidar, double stamp_s);
  Eigen::Isometry3d searchFirstMotion(const Scan& scan, const Eigen::Isometry3d& guess, FrameResult& res);
  void redeskewFirstFrame(const Eigen::Isometry3d& delta_sweep);

  Params params_;
  preprocess::PreprocessChain chain_;
  std::unique_ptr<ScanMatcher> matcher_;
  registration::AdaptiveThreshold threshold_;
  /// What the odometry knows of the vehicle's motion so far.
  struct Track {
    size_t frames = 0;           ///< frames processed, skipped ones included [-]
    bool have_pose = false;      ///< a frame got a pose (the first one: identity)
    bool motion_known = false;   ///< a frame after the first was registered (or a prior given)
    /// the last frame's motion was measured by its scans (or given by a prior), or repeats one that was
    bool motion_seen = false;
    double last_stamp_s = 0;     ///< stamp of the last frame with a pose [s]
    double last_dt_s = 0;        ///< time step of delta_last [s]
    Eigen::Isometry3d T_world_last = Eigen::Isometry3d::Identity();
    Eigen::Isometry3d delta_last = Eigen::Isometry3d::Identity();  ///< T_prev_curr of the last frame
    Eigen::Isometry3d T_world_keyframe = Eigen::Isometry3d::Identity();
  };
  /// The world's up direction, measured from every converged frame's vertical structures.
  struct UpEstimate {
    Eigen::Vector3d world = Eigen::Vector3d::UnitZ();    ///< measured up direction, world frame
    Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();   ///< verticalScatter summed over the frames
    int frames = 0;                                      ///< frames since `world` is known
  };
  /// This frame's deskewed points and what was found in them.
  struct FramePoints {
    std::vector<Eigen::Vector3d> points;        ///< deskewed, preprocessed, lidar frame [m]
    std::vector<uint8_t> ground;                ///< ground labels of points (when ground_aware_map)
    std::vector<VerticalConstraint> vertical;   ///< vertical structures (gravity prior)
  };
  /// One frame's predicted motion.
  struct Prediction {
    double dt = 0;  ///< time since the last frame with a pose [s]
    Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();        ///< T_prev_curr predicted
    Eigen::Isometry3d delta_sweep = Eigen::Isometry3d::Identity();  ///< motion over one sweep period
    Eigen::Isometry3d T_world = Eigen::Isometry3d::Identity();      ///< T_world_lidar predicted
    bool first_motion = false;  ///< the first frame after the first: its motion is unknown
  };
  Prediction predictFrame(const Scan& scan, const std::optional<MotionPrior>& prior, FrameResult& res);
  void deskewFrame(Scan& scan, const Prediction& pred, FrameResult& res);
  /// The first frame with points: identity pose. False when it has none (the frame is Empty).
  bool startTrack(const Scan& scan, size_t source_points, FrameResult& res);
  void registerFrame(const std::vector<Eigen::Vector3d>& source, const Eigen::Isometry3d& T_pred,
                     const std::optional<MotionPrior>& prior, FrameResult& res);
  void advance(FrameResult& res, const std::optional<MotionPrior>& prior, double dt, double stamp_s);

  Track track_;
  UpEstimate up_;
  FramePoints frame_;
  std::optional<Scan> first_scan_;  ///< the first sweep, preprocessed, until the motion is known
  std::vector<MapExclusion> exclusions_;  ///< setMapExclusions()
};

}  // namespace roadslam::odometry

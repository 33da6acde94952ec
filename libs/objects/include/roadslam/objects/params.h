#pragma once
/// \file params.h
/// Parameters of the objects stage: segmentation of a sweep's non-ground points into objects (ini
/// section [objects]) and their multi-object tracking in the map frame (section [tracking]).

#include <string>

#include "roadslam/preprocess/ground_segmentation.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::objects {

enum class ClusterMethod { RangeImage, Euclidean, Dbscan };
std::string toString(ClusterMethod m);
ClusterMethod clusterMethodFromString(const std::string& s);  ///< throws std::invalid_argument

/// Motion model of the tracks' Kalman filters: constant velocity (linear), constant turn rate and
/// velocity (extended KF), or an interacting multiple model of constant velocity and coordinated turn.
enum class MotionModel { ConstantVelocity, Ctrv, Imm };
std::string toString(MotionModel m);

/// [preprocess] max_range_m's default (libs/preprocess crop_filters), the reach [objects] max_range_m = 0 takes [m]
constexpr double kMapReachDefault_m = 100.0;

/// Segmentation ([objects]).
struct ClusterParams {
  bool enabled = false;                  ///< roadslam-map runs the objects stage and writes objects.csv, tracks.csv [-]
  ClusterMethod method = ClusterMethod::RangeImage;  ///< range_image (ring x azimuth), euclidean (xy grid) or dbscan [-]
  int azimuth_bins = 1800;               ///< range-image columns over 360 deg (VLP-16 at 10 Hz: 0.2 deg) [-]
  int azimuth_window = 3;                ///< range image: neighbours searched this many columns either side [-]
  int ring_window = 2;                   ///< range image: ... and this many rings above and below [-]
  double cluster_distance_m = 0.6;       ///< two points join one object when this close in x-y [m]
  double min_height_m = 0.25;            ///< non-ground points at least this high above the local ground [m]
  double max_height_m = 3.0;             ///< ... and at most this high (tree crowns, bridges out) [m]
  double min_range_m = 2.0;              ///< points nearer (x-y) are the own car's body, not segmented [m]
  /// Points beyond (x-y distance from the lidar) are not segmented; 0 in the ini: the sweeps' own reach,
  /// [preprocess] max_range_m (the point map keeps points to it: a car the stage does not reach leaves
  /// its trail) [m]
  double max_range_m = 100.0;
  int min_points = 8;                    ///< smaller clusters are no object [-]
  /// dbscan: a core point has this many points (itself included) within cluster_distance_m (Ester et
  /// al. 1996, MinPts; Open3D's cluster_dbscan min_points); other points join a core's cluster as its border [-]
  int dbscan_min_points = 4;
  double min_top_height_m = 0.5;         ///< clusters whose highest point is lower above the ground (curbs) are no object [m]
  double max_length_m = 12.0;            ///< longer clusters (walls, hedges) are no object [m]
  double max_width_m = 4.0;              ///< wider clusters are no object [m]
  double lshape_step_rad = 1.0 * 3.14159265358979323846 / 180.0;  ///< L-shape search step; ini `lshape_step_deg` [rad]
  /// Points of objects whose track is labelled moving stay out of the maps (point map, OctoMap, grid,
  /// keyframes; the odometry's own local map: the next key) [-]
  bool remove_moving_from_maps = true;
  /// ... and, predicted to the next sweeps, out of the odometry's own local map (libs/pipeline hands
  /// them to the pose stage: the objects stage runs after the odometry) [-]
  bool remove_moving_from_odometry = false;
  /// With remove_moving_from_odometry: each moving track's box also erases the odometry's local-map
  /// voxels it swept over this long before now (what the car left there before its moving label,
  /// ~1 s); 0: none [s]
  double odometry_erase_back_s = 0.0;
  double removal_margin_m = 0.3;         ///< around a moving object's box, x-y and z [m]
  /// With the removal: keyframes reach the OctoMap this long after their sweep, so that the points of a
  /// car labelled moving later (its first sweeps, before the label) leave the keyframes first [s]
  double map_delay_s = 6.0;
  /// When a track is labelled moving, the keyframes also lose the points inside car-sized boxes along
  /// the path its velocity leads back for this long before its birth (a car seen too far or sparse
  /// for an object) [s]
  double retro_extrapolate_s = 4.0;
  /// A moving track's removal boxes (coasting and retroactive) reach down to this height above the
  /// ground under its last detection, below the lowest point it was seen with: the -1 deg ring of a
  /// VLP-16 at 1.9 m hits a car 0.9 m above the road at 60 m and 0.15 m at 100 m, lower than any point
  /// the sweeps that track it from nearer find, so its far sweeps' points stayed under the box
  /// (libs/eval/tools/ghost_origins.py attributes such ghosts). A car's ground clearance: the road and curbs stay. Negative:
  /// the detections' lowest point only [m]
  double removal_floor_m = 0.2;
  /// A moving track that ends (its car fell below min_points, receding) keeps a box carried along its
  /// velocity for this long, so the car's last sparse sweeps leave the maps too; 0: none [s]
  double forward_extrapolate_s = 0.0;
  preprocess::GroundSegParams ground;    ///< ground labels: read from [preprocess] seg_* (the odometry's), not saved here
  /// The objects' own ground labels let a new ground line bridge at most this far from the last ground
  /// prototype (GroundSegParams::max_bridge_m, 30 m for the odometry): a far car's face, hit by one ring
  /// (VLP-16 at 1.9 m: the -1 deg ring beyond the -3 deg ring's 36 m), is otherwise taken for a rise of
  /// the road and labelled ground. 0: the [preprocess] value [m]
  double ground_max_bridge_m = 8.0;
  /// Each object's points are checked against the sweep this long before (free_space.h): did its rays
  /// pass through where they are now (free before: a moving car) or end there (static)? The tracker's
  /// moving label reads it (TrackerParams::moving_min_free_fraction); 0: off [s]
  double free_space_lag_s = 1.0;
  double free_space_margin_m = 0.5;      ///< ... a ray passed through a point when it reached this much beyond it [m]
  /// The ground parameters the objects use: \ref ground with ground_max_bridge_m.
  preprocess::GroundSegParams groundParams() const;

  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "objects",
                          const std::string& ground_section = "preprocess");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "objects") const;
};

/// The CTRV model's process noise ([tracking] ctrv_* keys): state x, y, v (speed), psi (heading),
/// omega (turn rate); white noise on the longitudinal acceleration and the yaw acceleration
/// (Schubert et al., "Comparison and Evaluation of Advanced Motion Models for Vehicle Tracking", FUSION 2008).
struct CtrvParams {
  double accel_sigma_mps2 = 1.5;         ///< longitudinal acceleration noise [m/s^2]
  double yaw_accel_sigma_radps2 = 30.0 * 3.14159265358979323846 / 180.0;  ///< yaw acceleration noise; ini `yaw_accel_sigma_degps2` [rad/s^2]
  double init_yaw_rate_sigma_radps = 20.0 * 3.14159265358979323846 / 180.0; ///< turn rate uncertainty of a new track; ini `init_yaw_rate_sigma_degps` [rad/s]

  void fields(ParamTable& t);
};

/// The IMM's models and Markov chain ([tracking] imm_* keys): constant velocity and coordinated turn on
/// the state [x, y, vx, vy, omega] (Blom and Bar-Shalom 1988; Bar-Shalom, Li and Kirubarajan 2001,
/// Sec. 11.6.6 and 11.7). The chain leaves a model at the rate 1 / its mean sojourn time.
struct ImmParams {
  double cv_accel_sigma_mps2 = 1.5;      ///< CV model: white-acceleration noise (TrackerParams::accel_sigma_mps2's role) [m/s^2]
  double ct_accel_sigma_mps2 = 1.5;      ///< CT model: white-acceleration noise [m/s^2]
  /// Both models' white-acceleration noise for a track labelled moving: a proven car brakes and
  /// accelerates at 2-3 m/s^2, while clutter's unproven tracks keep the quieter models (they drift into
  /// the moving label otherwise). 0: the models' own [m/s^2]
  double moving_accel_sigma_mps2 = 2.5;
  double ct_turn_accel_sigma_radps2 = 360.0 * 3.14159265358979323846 / 180.0;  ///< CT model: turn-rate noise (a simulated corner: 60 deg/s within 0.3 s); ini `imm_ct_turn_accel_sigma_degps2` [rad/s^2]
  double init_turn_rate_sigma_radps = 20.0 * 3.14159265358979323846 / 180.0;  ///< CT turn rate uncertainty of a new track; ini `imm_init_turn_rate_sigma_degps` [rad/s]
  /// CT model: the turn rate is clamped to this and its standard deviation capped at it (a static
  /// object's turn rate is unobservable); ini `imm_max_turn_rate_degps` [rad/s]
  double max_turn_rate_radps = 180.0 * 3.14159265358979323846 / 180.0;
  double cv_sojourn_s = 4.0;             ///< mean time in the CV model before a turn [s]
  double ct_sojourn_s = 2.0;             ///< mean time in the CT model (a turn at a junction) [s]
  double init_ct_probability = 0.1;      ///< CT model probability of a new track [-]

  void fields(ParamTable& t);
};

/// Tracking ([tracking]): a Kalman filter per track in the map frame (constant velocity, or CTRV as
/// an extended KF), global nearest-neighbour association (Hungarian on gated x-y distances), birth,
/// confirmation, death.
struct TrackerParams {
  MotionModel motion_model = MotionModel::Imm;  ///< cv, ctrv or imm [-]
  CtrvParams ctrv;                       ///< motion_model = ctrv: keys ctrv_*
  ImmParams imm;                         ///< motion_model = imm: keys imm_*
  double gate_m = 2.5;                   ///< a detection farther than this from a track's prediction is no match [m]
  double gate_sigma = 3.0;               ///< ... or farther than this many standard deviations (innovation covariance) [-]
  double size_weight = 0.5;              ///< association cost per metre of extent difference (along + across) [-]
  double accel_sigma_mps2 = 1.5;         ///< white-acceleration process noise of the CV model [m/s^2]
  double meas_sigma_m = 0.25;            ///< detection position noise [m]
  /// motion_model = imm: a moving track's heading is also measured by its box's axis nearest the
  /// velocity (within 30 deg), with this standard deviation (the L-shape turns with the car, the
  /// velocity from the centres lags); 0: off (the default: on KITTI raw 0001 a real car's box axes
  /// pulled the heading 3-7 deg off at 10 deg and lost the car at 5 deg; docs/benchmarks.md); ini
  /// `heading_sigma_deg` [rad]
  double heading_sigma_rad = 0.0;
  double init_speed_sigma_mps = 10.0;    ///< speed uncertainty of a new track [m/s]
  int confirm_hits = 3;                  ///< hits that confirm a tentative track [-]
  int max_misses = 5;                    ///< consecutive misses (sweeps) that end a confirmed track [-]
  /// Confirmed tracks that missed more sweeps in a row stay out of the outputs (ObjectsFrame::tracks:
  /// tracks.csv, the picture) while they still coast and associate until max_misses: a constant-velocity
  /// prediction 0.3 s on (through a turn, past a car lost behind another) is no estimate (SORT outputs
  /// only the tracks updated in the frame) [-]
  int output_max_misses = 2;
  /// consecutive misses a tentative track survives (a far car's face is seen every other sweep when
  /// one ring hits it too low for an object) [-]
  int tentative_max_misses = 1;
  double moving_speed_mps = 4.0;         ///< a confirmed track faster than this (14 km/h; slower cars stay static) ... [m/s]
  double moving_min_travel_m = 3.0;      ///< ... that has moved this far from its birth ... [m]
  int moving_min_hits = 10;              ///< ... and was detected this many times is labelled moving [-]
  /// ... unless its points were found where the earlier sweep's rays ended (static clutter whose box
  /// slides as the car turns): of its recent points with evidence (ClusterParams::free_space_lag_s;
  /// at least 10, weighted 0.8 per detection back), at least this share must lie where those rays
  /// passed through; 0: off [-]
  double moving_min_free_fraction = 0.5;
  double max_extent_growth_m = 6.0;      ///< a partly seen detection is completed to at most this length (cars) [m]
  double moving_max_length_m = 7.0;      ///< tracks ever seen longer than this (walls seen in parts) are never moving [m]
  double moving_max_width_m = 3.0;       ///< ... or wider than this [m]
  double moving_min_width_m = 1.0;       ///< ... or never seen wider than this (a wall's face slides, a car shows two faces) [m]
  double moving_max_height_m = 2.3;      ///< ... or ever seen higher above the ground (walls, hedges; cars and SUVs stay below, vans and trucks not) [m]
  /// A track confirmed within this distance (x-y) of where a moving track that lost its object two
  /// sweeps ago is predicted continues the lost track (its id, age, label; the object left the gate
  /// and came back as a new track); 0: off [m]
  double reid_gate_m = 3.0;
  /// ... when the lost track is faster than this: static clutter passed at a corner, labelled moving
  /// as its objects merge and split, was at 4.6 and 5.8 m/s when it lost its boxes (90 s urban loop);
  /// the cars that did so drove at 10.3 m/s (median) [m/s]
  double reid_min_speed_mps = 6.0;
  double max_dt_s = 1.0;                 ///< a gap longer than this between sweeps ends every track ("gap") [s]
  /// Car-size prior of the box centre: a moving track's detections are completed to at least this
  /// size away from the sensor (0 = off) ... [m]
  double car_length_m = 4.5;
  double car_width_m = 1.8;              ///< [m]
  /// ... and, with no heading known yet, a single face seen from this range or farther (no side visible) ... [m]
  double car_prior_min_range_m = 12.0;
  double car_face_min_m = 1.2;           ///< ... this wide at least ... [m]
  double car_face_max_m = 2.4;           ///< ... and at most (a front or rear; longer faces are sides) ... [m]
  double car_face_max_depth_m = 0.6;     ///< ... and this thin along the line of sight is a car's face, its centre car_length_m/2 behind [m]

  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "tracking");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "tracking") const;
};

}  // namespace roadslam::objects

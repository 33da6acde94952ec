#pragma once
/// \file params.h
/// Parameters of the road-boundary detector (ini section [boundary], ground labelling in [ground]).
/// Frames: "vehicle" is the lidar frame projected on its xy plane (x forward, y left) [m]; "map" is
/// the frame of the poses given with each sweep (T_map_lidar).

#include <cmath>
#include <string>

#include "roadslam/objects/params.h"
#include "roadslam/preprocess/ground_segmentation.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::boundary {

/// Boundary fit: `ransac` (curb points along the rings, RANSAC polynomial per side) or `thesis`
/// (the MATLAB thesis baseline: clusters -> rectangles -> RANSAC line over their inner corners).
enum class Method { Ransac, Thesis };

/// The ini name of \p m (`ransac`, `thesis`).
std::string toString(Method m);
/// The method named \p name; throws std::invalid_argument listing the valid names for an unknown one.
Method methodFromString(const std::string& name);

struct Params {
  Method method = Method::Ransac;  ///< ini key `method`: ransac | thesis

  // Curb detection: a low point whose 3x3-cell neighbourhood spans a curb height, next to ground,
  // with nothing taller in reach (the rings of a VLP-16 cross curbs ahead at grazing angles, so the
  // step is read in space, not along one ring; cf. Zhang et al. 2018 elevation-difference feature).
  double curb_min_jump_m = 0.05;      ///< smallest curb height [m]
  double curb_max_jump_m = 0.30;      ///< largest curb height [m]
  double curb_cell_m = 0.20;          ///< cell of the height-difference grid (3x3 neighbourhood) [m]
  int curb_reach_cells = 2;           ///< the step is read over (2k+1)^2 cells: far rings meet curbs at grazing angles and climb them over a metre or more [-]
  double curb_face_margin = 0.2;      ///< a face point lies above road + m * jump and below top - m * jump [-]
  int curb_clearance_cells = 2;       ///< no tall cell within this many cells of a curb point [-]
  /// No low return more than curb_max_jump_m below a step's bottom within this many cells [-]; 0 = off:
  /// the step then stands on something (a car's end face that the ground line followed), not on the road.
  int curb_level_cells = 0;
  /// Curb-map cells within this many cells of a point some sweep saw standing (tall_height_m to
  /// tall_max_height_m above the ground) are dropped: from afar a grazing ring reads a car's end face
  /// as a low step, from nearer the same face stands [-]; -1 = off.
  int curb_veto_cells = -1;
  double curb_veto_range_m = 40.0;  ///< only points this near the sensor veto [m]
  double curb_max_range_m = 40.0;     ///< rings farther than this are too sparse to read [m]
  /// Nearer points are never curb [m]; 0 = off: inside the lowest beam's blind circle on the road
  /// (VLP-16, -15 deg at 1.9 m: road from 7.1 m, a 0.30 m curb's face from 6.0 m) a return is not on
  /// the road the vehicle stands on but on what stands on it (the ends of perpendicular-parked cars,
  /// parked cars' sills: the ground lines of their sectors start on the body, which reads as a low step).
  /// Off by default, on in ini/bounds-parking.ini (docs/apps/roadslam-bounds.md).
  double curb_min_range_m = 0.0;
  double tall_cell_m = 0.5;           ///< xy cell of the "something taller here" test [m]
  double tall_height_m = 0.40;        ///< a cell with a point between this ... [m]
  double tall_max_height_m = 1.5;     ///< ... and this high above ground is no curb (tree crowns above pass) [m]

  // Obstacles: non-ground points between these heights above the local ground, grouped by the
  // objects stage's segmentation (objects::segmentObjects: one clustering for objects and obstacles),
  // without its size and height filters (walls and hedges are obstacles too).
  double obstacle_min_height_m = 0.30;  ///< lower bound [m]
  double obstacle_max_height_m = 3.0;   ///< upper bound (overhangs, tree crowns above) [m]
  /// range_image (ring x azimuth; sweeps without rings fall back to euclidean), euclidean or dbscan [-]
  objects::ClusterMethod cluster_method = objects::ClusterMethod::RangeImage;
  double cluster_distance_m = 0.6;      ///< two obstacle points join one cluster when this close in x-y [m]
  int cluster_min_points = 5;           ///< smaller clusters are noise [-]
  double roi_range_m = 40.0;            ///< obstacles, free space and grid within this range [m]

  // Free space: polar grid from the sensor.
  int freespace_sectors = 180;          ///< azimuth sectors over 360 deg [-]

  // Boundary fit (vehicle frame; the polynomial in the arc frame of the driven path, see below).
  double band_min_x_m = 5.0;            ///< reported band ahead, start [m]
  double band_max_x_m = 30.0;           ///< reported band ahead, end [m]
  double fit_min_x_m = -10.0;           ///< points used for the fit, from [m]
  double fit_max_x_m = 40.0;            ///< ... to [m]
  double min_lateral_m = 1.0;           ///< |y| of candidates, lower bound [m]
  double max_lateral_m = 15.0;          ///< |y| of candidates, upper bound [m]
  int poly_degree = 2;                  ///< y = c0 + c1 x + c2 x^2 (1 or 2) [-]
  double max_heading = 0.5;             ///< |dy/dx| of a boundary at x = 0 (|c1|) [-]
  double max_curvature = 0.05;          ///< |c2| = 1 / (2 R): 0.05 allows a 10 m radius [1/m]
  double ransac_inlier_m = 0.12;        ///< RANSAC inlier distance [m]
  int ransac_iterations = 800;          ///< [-] (200 left whole-drive figures seed-dependent)
  int ransac_seed = 7;                  ///< fixed seed: same input, same output [-]
  double bin_m = 1.0;                   ///< distance bins along x for coverage [m]
  int min_bins = 5;                     ///< fewer covered bins: side unknown [-]
  int min_band_bins = 3;                ///< ... and at least this many of them in the band ahead [-]
  double inner_curb_share = 0.5;        ///< a parallel line >= 2.5 m nearer the vehicle (fit.cpp kInnerGap) with this share of the best line's bins is the curb (the best a sidewalk's far edge); 0 = off [-]
  double polyline_step_m = 1.0;         ///< output polyline vertex spacing [m]

  // Time: curb evidence of many sweeps in a CurbMap (map frame), moved with the vehicle; cells
  // behind fit_min_x_m are dropped.
  int memory_frames = 300;              ///< a curb cell not seen again for this many sweeps is dropped [-]
  double curb_map_cell_m = 0.2;         ///< cell of the curb map (map frame) [m]
  double curb_map_radius_m = 60.0;      ///< cells farther from the vehicle are dropped [m]
  int curb_min_sightings = 1;           ///< cells seen by fewer sweeps are not fitted [-]
  /// Whole-drive mode (BoundaryDetector::finishAccumulation): cells seen by fewer sweeps are not
  /// fitted [-]. A curb cell is seen by tens of sweeps over a drive; a stray curb label (a ring
  /// grazing the curb from alongside, 0.1-0.5 m off it) by one or two, and over a whole drive the
  /// strays of one stretch fill as many bins beside the curb as the curb itself.
  int whole_drive_min_sightings = 3;
  double path_step_m = 1.0;             ///< whole-drive mode: vertex spacing of the drive's path frame [m]
  double max_extrapolation_m = 5.0;     ///< the polyline ends this far beyond the last evidence [m]
  double max_bridge_m = 12.0;           ///< longest gap between curb stretches the polyline spans [m]
  int max_hold_frames = 3;              ///< a side not seen is held (moved with the vehicle) this long [-]
  double track_gate_m = 0.5;            ///< a new fit farther than this from the held side is an outlier [m]
  double hold_decay = 0.85;             ///< confidence factor per held sweep [-]
  double hold_max_turn_rad = 2.0 * M_PI / 180.0;     ///< a held side is dropped once the vehicle turned this much since its fit (ini: hold_max_turn_deg) [rad]
  /// Sides are fitted along the arc the vehicle drives (curvature = heading change / path length
  /// over this many past sweeps) so they follow corners; 0 = in the vehicle frame [-].
  int path_curvature_frames = 5;
  double path_min_length_m = 2.0;       ///< shorter paths over those sweeps give curvature 0 [m]
  /// Corner entries and exits: the frame may bend ahead of the vehicle (the driven path's arc up to
  /// s_bend, then another curvature) where that lines up the curb map's cells at constant offsets on
  /// both sides by bend_margin_bins more 1 m bins than the path's arc alone (src/bend_frame.cpp).
  double bend_max_curvature = 0.12;     ///< largest curvature tried after the bend (radius 8.3 m); 0 disables [1/m]
  int bend_curvature_steps = 6;         ///< curvatures tried on each side of 0: max * k / steps [-]
  double bend_step_m = 3.0;             ///< s_bend tried at 0, step, ... below band_max_x_m [m]
  int bend_margin_bins = 8;             ///< votes (1 m bins, both sides) a bend must add to replace the path's arc [-]
  /// A side whose own curb cells end early (parked cars hide it ahead) continues parallel to the
  /// other side at the offset measured on its own cells, when their offsets to the other side
  /// spread (median absolute deviation) at most this much; 0 disables [m].
  double parallel_max_spread_m = 0.15;
  double parallel_width_gate_m = 0.3;   ///< ... and when that offset is within this of the road's width measured where both sides had their own fit [m]
  /// Both sides fitted with curb to curb (at band_min_x_m) off the road's width by more than this:
  /// the side that left its track is refitted near the other side moved by the width; 0 disables [m].
  double width_jump_m = 3.0;

  // Cost grid for a planner (vehicle frame).
  double grid_resolution_m = 0.2;       ///< [m]
  double grid_size_m = 60.0;            ///< square side, centred 15 m ahead of the vehicle [m]

  preprocess::GroundSegParams ground;   ///< ground labelling (section [ground], keys seg_*)

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section = "boundary",
                          const std::string& ground_section = "ground");
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section = "boundary",
                        const std::string& ground_section = "ground") const;
};

}  // namespace roadslam::boundary

#pragma once
/// \file spec.h
/// An experiment file (EXP.ini, the MRPT ini style of the other configs): a base config, datasets,
/// the stages to run and the parameters to sweep. Paths are relative to the EXP.ini's folder.
///
///     [experiment]
///     name = voxel-size
///     base_config = ../default.ini        ; the config every job starts from
///     stages = odometry, eval             ; odometry | map | bounds | eval
///     max_frames = 0                      ; per job, 0 = all
///     bounds_poses = auto                 ; bounds stage poses: auto | gt | odometry
///
///     [dataset.urban]                     ; one section per dataset
///     scenario = ../sim/urban-loop.ini    ; simulated once into OUT/data/urban (its GT with it)
///     duration_s = 30
///     [dataset.kitti-0001]
///     input = ../../../shared/data/...    ; .pcap, .rawlog or KITTI folder
///     gt = ...                            ; TUM or KITTI poses (gt_times, gt_calib for KITTI)
///
///     [sweep]
///     mode = grid                         ; grid | zip | random (samples, seed)
///     odometry.registration_voxel_m = 0.5, 0.75, 1.0
///     experiment.base_config = ../thesis-icp.ini, ../thesis-ndt.ini   ; a sweep over whole configs
///     ; random mode: a list to draw from, or uniform(a, b), loguniform(a, b), randint(a, b)
///
/// Everything is checked before any job starts; errors name the file and line.

#include <cstdint>
#include <string>
#include <vector>

namespace roadslam::experiment {

enum class Stage { Odometry, Map, Bounds, Eval };
const char* toString(Stage s);

/// Where the bounds stage takes its poses: the map/odometry stage's trajectory when one ran, else
/// the ground truth (auto); or always the GT; or always its own odometry.
enum class BoundsPoses { Auto, Gt, Odometry };

struct Dataset {
  std::string name;        ///< from [dataset.NAME]
  std::string input;       ///< recording (absolute); for a simulated dataset filled by prepareDatasets
  std::string times;       ///< KITTI folder: its times file (optional)
  std::string gt;          ///< ground-truth trajectory, TUM or KITTI (optional)
  std::string gt_times;    ///< KITTI-format GT: its times file
  std::string gt_calib;    ///< KITTI odometry calib.txt (camera GT -> lidar)
  std::string gt_boundaries;  ///< simulator's gt_boundaries.json (bounds scoring)
  std::string scenario;    ///< simulator scenario ini: the dataset is simulated
  double duration_s = 0;   ///< simulated seconds (0 = the scenario's own)
  int line = 0;            ///< line of the section's first key in the EXP.ini
};

enum class SweepMode { Grid, Zip, Random };

struct SweepParam {
  std::string section, key;         ///< "odometry", "registration_voxel_m"; "experiment", "base_config"
  std::vector<std::string> values;  ///< grid/zip; random: a list to draw from
  std::string distribution;         ///< random: "uniform", "loguniform", "randint" (empty: the list)
  double lo = 0, hi = 0;            ///< the distribution's range
  int line = 0;
  std::string name() const { return section + "." + key; }
};

struct ExperimentSpec {
  std::string path;         ///< the EXP.ini (absolute)
  std::string name;
  std::string base_config;  ///< absolute
  std::vector<Stage> stages;
  size_t max_frames = 0;
  BoundsPoses bounds_poses = BoundsPoses::Auto;
  std::vector<Dataset> datasets;
  SweepMode mode = SweepMode::Grid;
  size_t samples = 0;       ///< random mode: configurations drawn
  uint64_t seed = 1;        ///< random mode
  std::vector<SweepParam> sweep;
  bool has(Stage s) const;
};

/// Reads and checks \p path: unknown keys and sections (nearest known named), missing files,
/// stages, sweep keys that no component of a job reads (nearest known named), values that do not
/// parse. Throws std::runtime_error "FILE:LINE: ..." with every problem found.
ExperimentSpec loadExperiment(const std::string& path);

/// Every "section.key" a job's components read from a config (the effective config of the map and
/// bounds jobs), e.g. "odometry.registration_voxel_m".
std::vector<std::string> knownConfigKeys(const std::string& config_path);

}  // namespace roadslam::experiment

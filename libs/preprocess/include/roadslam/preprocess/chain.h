#pragma once
/// \file chain.h
/// The preprocessing chain: an ordered, ini-configured list of filters applied in place to each
/// sweep (lidar frame), each step timed (wall clock) and counted. Non-finite points are always
/// dropped first and counted. Frame skipping (thesis `skipF`) decides which frames are processed.
///
/// The thesis's MATLAB keys are accepted as aliases with the meaning of the MATLAB calls they fed:
/// `maxD`, `maxAngD` = maxDistance [m] and maxAngularDistance [deg] of pcfitplane (ground plane
/// constrained to a reference vector); `downS` = percentage of pcdownsample(pc, 'random', p), the
/// fraction of points KEPT; `skipF` = frame step (frames 0, skipF, 2 skipF, ... processed; 1 = all);
/// `rad` = ego radius [m]; `xL`, `yL` = ROI half-widths [m] (box [-xL, xL] x [-yL, yL]). The thesis
/// code itself was not available to check `skipF`, `xL`, `yL` against: re-check when it is.
///
/// Ini section (all keys optional; SI units, thesis names accepted as aliases):
/// \code
/// [preprocess]
/// filters = ego,range,roi,ground_ransac,voxel   ; ego|range|roi|ground_ransac|ground_linefit|random|voxel|sor
/// keep_every_n_frames = 1      ; process frames 0, n, 2n, ... (thesis skipF)
/// ego_radius_m = 2.5           ; (rad)   see EgoParams, RangeParams, RoiParams, RansacGroundParams,
/// roi_half_x_m = 40            ; (xL)    GroundSegParams, RandomDownsampleParams, VoxelParams, SorParams
/// \endcode

#include "roadslam/common/scan.h"
#include "roadslam/preprocess/crop_filters.h"
#include "roadslam/preprocess/downsample.h"
#include "roadslam/preprocess/ground_segmentation.h"
#include "roadslam/preprocess/ransac_ground.h"

#include <string>
#include <vector>

namespace roadslam {
class ParamTable;
}

namespace roadslam::preprocess {

struct PreprocessParams {
  std::vector<std::string> filters{"ego", "range", "voxel"};  ///< chain order; ini `filters` (comma list)
  int keep_every_n_frames = 1;  ///< process every n-th frame [-]; ini `keep_every_n_frames`, thesis `skipF`
  EgoParams ego;
  RangeParams range;
  RoiParams roi;
  RansacGroundParams ransac;
  GroundSegParams ground_seg;
  RandomDownsampleParams random;
  VoxelParams voxel;
  SorParams sor;
  /// Keys of the section that no component knows (typos): filled by loadFromConfigFile, for the
  /// caller to report.
  std::vector<std::string> unknown_keys;

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Throws naming section/key on a malformed value, an unknown filter name or a key set twice
  /// (SI name and thesis alias).
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// Filter names accepted in `filters`.
const std::vector<std::string>& knownFilterNames();

struct FilterStepReport {
  std::string name;       ///< filter name as in `filters` ("non_finite" for the implicit first step)
  size_t points_in = 0;   ///< points entering the step
  size_t removed = 0;     ///< points removed by the step
  double wall_time_s = 0; ///< wall-clock time of the step [s]
};

/// What happened to one frame.
struct PreprocessReport {
  size_t frame_index = 0;    ///< 0-based count of frames given to process()
  bool skipped = false;      ///< true: frame skipping dropped it (points left untouched)
  size_t points_in = 0;      ///< points of the input sweep
  size_t points_out = 0;     ///< points left
  std::vector<FilterStepReport> steps;
  double wall_time_s = 0;    ///< total wall-clock time [s]
};

/// Sums over the frames processed so far.
struct PreprocessTotals {
  size_t frames = 0, skipped = 0, points_in = 0, points_out = 0;
  std::vector<FilterStepReport> steps;  ///< removed and wall_time_s summed per step
};

/// One line per step for run logs, e.g. "voxel: 1,234,567 in, 987,654 removed (80.0 %), 0.42 ms/frame".
std::string formatTotals(const PreprocessTotals& totals);

class PreprocessChain {
 public:
  /// Throws std::invalid_argument on an unknown filter name.
  explicit PreprocessChain(PreprocessParams params);

  /// Filters \p scan.points in place unless frame skipping drops this frame (then report.skipped
  /// is true and the caller should not use the sweep). Never throws on data: an empty or all-NaN
  /// sweep just yields 0 points.
  PreprocessReport process(Scan& scan);

  const PreprocessParams& params() const { return params_; }
  const PreprocessTotals& totals() const { return totals_; }

 private:
  size_t applyStep(const std::string& name, std::vector<ScanPoint>& pts) const;
  PreprocessParams params_;
  size_t next_frame_ = 0;
  PreprocessTotals totals_;
};

}  // namespace roadslam::preprocess

#include "roadslam/jobs/bounds_job.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <filesystem>
#include <map>
#include <optional>

#include "lidar_model_json.h"
#include "source_progress.h"
#include "roadslam/boundary/detector.h"
#include "roadslam/boundary/output.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/side_input.h"
#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/jobs/gnss_outputs.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/odometry/odometry.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/pipeline/stage_factory.h"
#include "roadslam/runfolder/output_folder.h"
#include "roadslam/runfolder/run_folder.h"
#include "roadslam/runfolder/boundaries.h"
#include "roadslam/runfolder/summary.h"

namespace fs = std::filesystem;

namespace roadslam::jobs {
namespace {

/// The found sides of a sweep as map-frame polylines for the geo outputs.
void addGeoLines(const boundary::BoundaryFrame& f, std::vector<GeoPolyline>& out) {
  for (const auto* side : {&f.left, &f.right}) {
    if (!side->found || side->polyline_map.size() < 2) continue;
    GeoPolyline l;
    l.stamp_s = f.stamp_s;
    l.side = side == &f.left ? "left" : "right";
    l.confidence = side->confidence;
    for (const auto& v : side->polyline_map) l.p_map.emplace_back(v.x, v.y, v.z);
    out.push_back(std::move(l));
  }
}

bool enough(const BoundsRequest& req, size_t sweeps) { return stopRequested() || (req.max_frames && sweeps >= req.max_frames); }

/// The stages of one pass over the drive: poses (a trajectory, \p recorded, else the odometry, which
/// keeps the sweeps: the detector needs them whole) and the boundaries.
pipeline::StageList boundsStages(const BoundsRequest& req, const odometry::Params& op, std::shared_ptr<boundary::BoundaryDetector> det,
                                 pipeline::BoundaryUse use, std::optional<std::vector<pipeline::SweepPose>> recorded = {}, const std::string& origin = "") {
  pipeline::ChainParams chain;
  chain.odometry = op;
  pipeline::StageRequest r;
  r.objects = false;
  r.boundaries = std::move(det);
  r.boundary_use = use;
  if (recorded) {
    r.recorded_poses = std::move(recorded);
    r.recorded_input = req.input_path;
    r.recorded_origin = origin;
  } else {
    r.trajectory_path = req.trajectory_path;
  }
  return pipeline::buildStages(chain, std::move(r));
}

struct Drive {
  std::vector<pipeline::SweepPose> poses;  ///< one per sweep, in order
  double ms_mean = 0;            ///< detector time per sweep (labelling, curb map) [ms]
};

/// Whole-drive mode, first pass over \p source: every sweep's pose from \p stages' pose stage (the
/// odometry runs here only) and its curb points into \p det's curb map (the boundary stage accumulates).
Drive accumulateDrive(const BoundsRequest& req, std::unique_ptr<sources::ScanSource> source, pipeline::StageList stages,
                      boundary::BoundaryDetector& det) {
  pipeline::Pipeline pipe(std::move(source), std::move(stages));
  SourceProgress bar("roadslam-bounds: whole drive, pass 1", pipe.source(), req.progress);
  Drive d;
  size_t n = 0;
  while (!enough(req, d.poses.size())) {
    auto f = pipe.next();
    if (!f) break;
    d.poses.push_back(std::move(f->pose));
    if (d.poses.back().ok) d.ms_mean += f->ms.of("boundaries"), ++n;
    bar.update(d.poses.size());
  }
  bar.finish();
  det.finishAccumulation();
  d.ms_mean /= static_cast<double>(std::max<size_t>(n, 1));
  return d;
}

struct Totals {
  size_t frames = 0, no_pose = 0, left = 0, right = 0, both = 0;
  double ms_sum = 0, ms_max = 0;
  std::map<std::string, size_t> status, reasons;
  void add(const boundary::BoundaryFrame& f) {
    ++frames, ++status[toString(f.status)];
    ms_sum += f.ms, ms_max = std::max(ms_max, f.ms);
    left += f.left.found, right += f.right.found, both += f.left.found && f.right.found;
    if (!f.left.found) ++reasons["left: " + f.left.reason.substr(0, f.left.reason.find(" ("))];
    if (!f.right.found) ++reasons["right: " + f.right.reason.substr(0, f.right.reason.find(" ("))];
  }
};

void drawFrame(const std::string& out_dir, const pipeline::PipelineFrame& pf, const boundary::BoundaryDetector& det,
               std::string& last_png) {
  const boundary::BoundaryFrame& f = *pf.boundary;
  char name[32];
  std::snprintf(name, sizeof name, "frames/%06zu.png", f.index);
  last_png = out_dir + "/" + name;
  boundary::drawTopView(last_png, *pf.scan, det.lastLabelling(), f, 8.0, det.fitCells(pf.pose.ref));
  std::snprintf(name, sizeof name, "frames/%06zu_cost.png", f.index);
  boundary::writeCostGridPng(out_dir + "/" + name, f.grid);
}

/// The poses given must be of the recording's drive and clock (common/side_input.h).
void checkTrajectory(const std::string& path, double recording_start_s) {
  const auto T = datasets::readTum(path);
  if (T.stamps_s.empty()) throw std::runtime_error("--trajectory " + path + ": no pose in it");
  const std::string why = sideInputMismatch("--trajectory " + path, T.stamps_s.front(), T.stamps_s.back(), recording_start_s);
  if (!why.empty()) throw std::runtime_error(why);
}

}  // namespace

nlohmann::json runBoundsJob(const BoundsRequest& req) {
  const auto cfg = loadIniFile(req.config_path);
  boundary::Params params;
  params.loadFromConfigFile(*cfg);
  // what the sweeps' source and the odometry read, in every mode, so their keys are checked too
  odometry::Params op;
  op.loadFromConfigFile(*cfg);
  sources::loadSourceSections(*cfg);
  const auto unknown_keys = cfg->checkEntries(req.allow_unknown_keys);
  double start_s = 0;
  auto source = pipeline::openNonEmptySource(req.input_path, *cfg, req.times_path, &start_s);
  if (!req.trajectory_path.empty()) checkTrajectory(req.trajectory_path, start_s);
  // a trajectory or georeference that cannot be read fails here, before any output
  auto det = std::make_shared<boundary::BoundaryDetector>(params);
  pipeline::StageList stages = boundsStages(req, op, det, req.whole_drive ? pipeline::BoundaryUse::Accumulate : pipeline::BoundaryUse::Detect);
  std::optional<Georef> georef;
  if (!req.georef_path.empty()) georef = readGeoref(req.georef_path);
  std::vector<GeoPolyline> geo_lines;
  const auto forced = runfolder::claimOutputFolder(
      req.out_dir, {runfolder::kBoundsProgram, req.input_path, "", "",
                    {req.config_path, req.trajectory_path, req.georef_path, req.times_path}, req.force});
  std::error_code ec;
  fs::create_directories(req.out_dir + "/frames", ec);
  if (ec) throw std::runtime_error("cannot create output folder '" + req.out_dir + "': " + ec.message());
  mrpt::config::CConfigFileMemory used;
  params.saveToConfigFile(used);
  writeFileAtomically(req.out_dir + "/config_used.ini", used.getContent());
  Drive drive;  // whole-drive mode: pass 1's poses, replayed in pass 2
  if (req.whole_drive) {
    const std::string origin = static_cast<const pipeline::PoseStage&>(*stages.front()).describe();
    drive = accumulateDrive(req, std::move(source), std::move(stages), *det);
    stages = boundsStages(req, op, det, pipeline::BoundaryUse::Detect, drive.poses, origin);
    source = sources::openScanSource(req.input_path, *cfg, req.times_path);
  }
  pipeline::Pipeline pipe(std::move(source), std::move(stages));
  AtomicFile jsonl(req.out_dir + "/boundaries.jsonl");
  Totals tot;
  SourceProgress bar("roadslam-bounds", pipe.source(), req.progress);
  std::string last_png;
  while (!enough(req, pipe.frames()) && !(req.whole_drive && pipe.frames() >= drive.poses.size())) {
    const auto pf = pipe.next();
    if (!pf) break;
    if (!pf->boundary) {
      ++tot.no_pose;
      jsonl.stream() << runfolder::noPoseLine(pf->pose.stamp_s, pf->pose.why);
      continue;
    }
    tot.add(*pf->boundary);
    jsonl.stream() << toJson(*pf->boundary).dump() << "\n";
    if (georef) addGeoLines(*pf->boundary, geo_lines);
    if (req.png_every > 0 && pf->boundary->index % static_cast<size_t>(req.png_every) == 0) drawFrame(req.out_dir, *pf, *det, last_png);
    bar.update(tot.frames);
  }
  bar.finish();
  jsonl.commit();
  if (georef) writeGeoBoundaries(req.out_dir, geo_lines, *georef);
  if (!last_png.empty()) fs::copy_file(last_png, req.out_dir + "/top_view.png", fs::copy_options::overwrite_existing);
  const sources::ScanSource& stream = pipe.source();
  const double n = static_cast<double>(std::max<size_t>(tot.frames, 1));
  nlohmann::json s = {{"input", stream.describe()}, {"input_id", runfolder::canonicalPath(req.input_path)}, {"method", toString(params.method)}, {"frames", tot.frames},
                      {"frames_without_pose", tot.no_pose}, {"ms_per_frame_mean", tot.ms_sum / n},
                      {"ms_per_frame_max", tot.ms_max}, {"left_found_rate", tot.left / n},
                      {"right_found_rate", tot.right / n}, {"both_found_rate", tot.both / n},
                      {"status", tot.status}, {"not_found_reasons", tot.reasons},
                      {"poses", req.trajectory_path.empty() ? "odometry" : req.trajectory_path},
                      {"geo_boundaries", geo_lines.size()},
                      {"mode", req.whole_drive ? "whole_drive" : "live"}, {"curb_map_cells", det->curbMap().size()}};
  if (req.whole_drive) s["ms_per_frame_first_pass_mean"] = drive.ms_mean;
  addLidarModel(s, stream);
  s["warnings"] = unknown_keys;
  for (const auto& w : forced) s["warnings"].push_back(w);
  if (!stream.errorMessage().empty()) s["warnings"].push_back(sources::damageWarning(stream));
  s["interrupted"] = stopRequested();  // Ctrl-C / SIGTERM: the outputs so far, as roadslam-map's
  s["complete"] = stream.errorMessage().empty() && !stopRequested();
  for (const auto& w : stream.warnings()) s["warnings"].push_back(w);
  runfolder::writeSummaryJson(req.out_dir + "/summary.json", s);
  // run.json last: the folder is complete (docs/run-folder.md)
  runfolder::writeManifest(req.out_dir, runfolder::manifestFor(runfolder::kBoundsProgram, s));
  return s;
}

}  // namespace roadslam::jobs

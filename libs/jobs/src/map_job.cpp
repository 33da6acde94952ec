#include "roadslam/jobs/map_job.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "lidar_model_json.h"
#include "map_job_params.h"
#include "map_run_files.h"
#include "map_sinks.h"
#include "source_progress.h"
#include "roadslam/can/candump.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/common/side_input.h"
#include "roadslam/common/config.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/jobs/gnss_outputs.h"
#include "roadslam/mapping/map_outputs.h"
#include "roadslam/pipeline/can_prior.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/pipeline/stage_factory.h"
#include "roadslam/pipeline/stages/localization.h"
#include "roadslam/pipeline/stages/maps.h"
#include "roadslam/pipeline/stages/objects.h"
#include "roadslam/pipeline/stages/sweep_export.h"
#include "roadslam/runfolder/output_folder.h"
#include "roadslam/runfolder/run_folder.h"
#include "roadslam/sources/scan_source.h"

namespace fs = std::filesystem;

namespace roadslam::jobs {
namespace {

nlohmann::json loopsJson(const mapping::Mapper& m) {
  nlohmann::json acc = nlohmann::json::array(), rej = nlohmann::json::array();
  for (const auto& l : m.loopResults()) {
    const auto& kq = m.keyframes()[l.query];
    const auto& km = m.keyframes()[l.match];
    nlohmann::json j = {{"query_frame", kq.frame_index}, {"match_frame", km.frame_index},
                        {"query_keyframe", l.query}, {"match_keyframe", l.match},
                        {"fitness_m", l.fitness_m}, {"overlap", l.overlap},
                        {"correction_m", l.correction_m}, {"ms", l.ms}, {"reason", l.reason}};
    (l.accepted ? acc : rej).push_back(j);
  }
  return {{"accepted", acc}, {"rejected", rej}};
}

/// Appends the fixes of the GPS source \p label to \p kept.
void keepFixes(const std::vector<gnss::GnssFix>& fixes, const std::string& label,
               std::vector<gnss::GnssFix>& kept) {
  for (const auto& f : fixes)
    if (f.label == label) kept.push_back(f);
}

/// How far before a GNSS log's first fix the recording may start [s]: a receiver's cold start
/// (time to first fix) takes up to a few minutes.
constexpr double kGnssSlack_s = 300.0;

/// The GNSS the request asks to fuse: an NMEA log (read before the run: a bad log fails before hours
/// of processing), or the GPS source of the input chosen by label; their fixes are taken per sweep.
struct GnssRequest {
  std::optional<GnssInput> input;
  bool from_input = false;
  std::string label;
  std::vector<gnss::GnssFix> fixes;

  GnssRequest(const MapRequest& req, const gnss_fusion::GnssFusionParams& p, double recording_start_s)
      : from_input(req.gnss_from_input) {
    if (!req.gnss_path.empty() && req.gnss_from_input) throw std::runtime_error("--gnss and --gnss-from-input exclude each other");
    if (!req.gnss_path.empty()) {
      input = readGnssInput(req.gnss_path, p);
      // a receiver's first fix may come minutes after power-on (cold start): a wider slack than CAN's
      const std::string why = sideInputMismatch("--gnss " + req.gnss_path, input->factors.front().t_s,
                                                input->factors.back().t_s, recording_start_s, kGnssSlack_s);
      if (!why.empty()) throw std::runtime_error(why);
    }
    if (!req.gnss_label.empty() && !req.gnss_from_input) throw std::runtime_error("--gnss-label needs --gnss-from-input");
    if (req.gnss_from_input) label = chooseGpsSource(sources::gpsSourcesOf(req.input_path), req.gnss_label, req.input_path);
  }
  void take(sources::ScanSource& src) {
    if (from_input) keepFixes(src.takeGpsFixes(), label, fixes);
  }
};

/// A CAN log for the prior must be of the recording's drive and clock (common/side_input.h).
void checkCanLog(const std::string& path, double recording_start_s) {
  const auto span = can::candumpSpan(path);
  if (!span) throw std::runtime_error("--can " + path + ": no CAN frame in it");
  const std::string why = sideInputMismatch("--can " + path, span->first_s, span->last_s, recording_start_s);
  if (!why.empty()) throw std::runtime_error(why);
}

/// What the job collects from the pipeline's frames.
struct Sinks {
  ObjectsOutput objects;
  LocalizationOutput localization;
};

/// The pipeline's frames into \p out and the sinks until the source ends, the request's limit or a stop.
void drive(pipeline::Pipeline& pipe, const MapRequest& req, GnssRequest& gnss, Sinks& sinks, MapOutcome& out) {
  pipeline::ObjectTrackingStage* objects = pipe.find<pipeline::ObjectTrackingStage>();
  const bool localize = pipe.find<pipeline::LocalizationStage>() != nullptr;
  SourceProgress bar("roadslam-map", pipe.source(), req.progress);
  while (!stopRequested()) {
    if (req.max_frames && out.frames.size() >= req.max_frames) break;
    auto f = pipe.next();
    if (!f) break;
    gnss.take(pipe.source());
    if (objects) sinks.objects.add(*f, objects->objects());
    if (localize) sinks.localization.add(*f);
    out.frames.push_back(std::move(*f->pose.odometry));
    bar.update(out.frames.size());
  }
  pipe.finish();
  bar.finish();
  out.interrupted = stopRequested();
}

/// The input's part of the summary: its warnings, damage and statistics.
void summarizeInput(const sources::ScanSource& stream, const MapJobParams& params, MapOutcome& out) {
  const std::string damage = sources::damageWarning(stream);
  if (!damage.empty()) out.summary["warnings"].push_back(damage);
  out.summary["complete"] = damage.empty() && !out.interrupted;
  for (const auto& w : stream.warnings()) out.summary["warnings"].push_back(w);
  const int timed = out.summary["deskewed_frames"].get<int>();
  const int posed = static_cast<int>(out.frames.size()) - out.summary["frames_by_status"].value("skipped", 0);
  if (params.chain.odometry.deskew && timed < posed) {
    out.summary["warnings"].push_back("deskew = true, but " + std::to_string(posed - timed) + " of " +
                                      std::to_string(posed) + " sweeps carry no point times and were not deskewed "
                                      "(set [odometry] times_from_azimuth or the source's [kitti] times_from_azimuth)");
  }
  const auto st = stream.stats();
  out.summary["input"] = stream.describe();
  addLidarModel(out.summary, stream);
  out.summary["packets"] = st.packets;
  out.summary["malformed_packets"] = st.malformed_packets;
  out.summary["partial_sweeps"] = st.partial_sweeps;
  out.summary["interrupted"] = out.interrupted;
}

/// The maps stage's outputs: the loops, the seen-through removal, the map files.
void writeMapsStage(const MapRequest& req, const MapJobParams& params, pipeline::MapsStage& maps, const Sinks& sinks,
                    const pipeline::StageTimes& ms, MapOutcome& out) {
  mapping::Mapper& mapper = maps.mapper();
  const auto loops = loopsJson(mapper);
  out.summary["loop_closures"] = loops["accepted"].size();
  out.summary["loop_candidates_rejected"] = loops["rejected"].size();
  out.summary["loops"] = loops;
  out.summary["can_edges"] = mapper.canEdges();
  out.summary["ms_mapping_total"] = ms.of("maps");
  std::vector<mapping::TopViewBox> boxes;
  for (const auto& [id, b] : sinks.objects.last_moving) boxes.push_back(b);
  if (params.chain.maps.seen_through.enabled) {
    const auto st = mapping::removeSeenThrough(mapper, params.chain.maps.point_map.voxel_m, params.chain.maps.seen_through);
    out.summary["seen_through"] = {{"voxels", st.voxels}, {"tested_voxels", st.tested_voxels},
                                   {"references", st.references}, {"dynamic_voxels", st.dynamic_voxels},
                                   {"removed_points", st.removed_points}, {"ms", st.ms}};
  }
  const auto m = mapping::writeMaps(req.out_dir, mapper, {out.T_map_lidar.begin(), out.T_map_lidar.end()},
                                    params.chain.maps, maps.octomap(), boxes);
  out.summary["maps"] = {{"points", m.points}, {"octomap_keyframes", m.octomap_keyframes},
                         {"octomap_leafs", m.octomap_leafs}, {"octomap_ms_per_keyframe", m.octomap_ms_per_keyframe},
                         {"grid_occupied_cells", m.grid_occupied}, {"grid_free_cells", m.grid_free},
                         {"ms_total", m.ms_total}};
}

/// GNSS fusion of the trajectory (batch, and the online mode replayed) and its small outputs (the
/// geo-referenced trajectories); returns the fused T_enu_lidar per stamp for the ENU maps (empty: none).
mapping::PoseVector writeGnss(const MapRequest& req, const MapJobParams& params, const sources::ScanSource& stream,
                              GnssRequest& gnss, MapOutcome& out, std::vector<double>& stamps) {
  if (gnss.from_input) {
    try {
      gnss.input = gnssInputFromFixes(gnss.fixes, "GPS fixes of " + stream.describe() + " (" + gnss.label + ")",
                                      params.gnss_fusion);
    } catch (const std::exception& e) {
      out.summary["warnings"].push_back(std::string("GNSS fusion not done: ") + e.what());
    }
  }
  if (!gnss.input) return {};
  mapping::PoseVector T, T_odom;
  for (size_t i = 0; i < out.frames.size(); ++i) {
    if (out.frames[i].status == odometry::FrameStatus::Skipped) continue;
    if (!stamps.empty() && out.frames[i].stamp_s <= stamps.back()) continue;
    stamps.push_back(out.frames[i].stamp_s);
    T.push_back(req.maps ? out.T_map_lidar[i] : out.frames[i].T_world_lidar);
    T_odom.push_back(out.frames[i].T_world_lidar);
  }
  mapping::PoseVector T_enu;
  out.summary["gnss"] = fuseAndWriteGnss(req.out_dir, stamps, T, *gnss.input, params.gnss_fusion, &T_enu);
  out.summary["gnss"]["online"] = writeOnlineGnss(req.out_dir, stamps, T_odom, *gnss.input, params.gnss_fusion);
  const auto& g = out.summary["gnss"];
  if (g["status"] != "ok") out.summary["warnings"].push_back("GNSS fusion not done: " + g["status"].get<std::string>());
  for (const auto& [name, n] : gnss.input->log.counters.named()) {
    if (n > 0 && name != "lines" && name != "sentences" && name != "epochs" && name != "fixes" && name != "unsupported sentence")
      out.summary["warnings"].push_back("GNSS log: " + std::to_string(n) + " x " + name);
  }
  return T_enu;
}

/// Runs \p write; a failure (a full disk, a file system error) is recorded in the summary's
/// "write_errors" and the run goes on to write the other outputs, so one lost file never loses the rest.
template <typename F>
void attempt(MapOutcome& out, F&& write) {
  try {
    write();
  } catch (const std::exception& e) {
    out.summary["write_errors"].push_back(e.what());
  }
}

}  // namespace

MapOutcome runMapJob(const MapRequest& req) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto cfg = loadIniFile(req.config_path);
  MapJobParams params;
  params.load(*cfg);
  const auto unknown_keys = cfg->checkEntries(req.allow_unknown_keys);
  if (!req.can_log_path.empty() && req.vehicle_ini_path.empty()) throw std::runtime_error("--can needs --vehicle (the car's vehicle ini)");
  pipeline::StageRequest stages;
  if (!req.prior_map_dir.empty()) stages.prior_map = mapping::readMapFolder(req.prior_map_dir);
  double start_s = 0;
  auto source = pipeline::openNonEmptySource(req.input_path, *cfg, req.times_path, &start_s);
  if (!req.can_log_path.empty()) checkCanLog(req.can_log_path, start_s);
  GnssRequest gnss(req, params.gnss_fusion, start_s);
  runfolder::OutputClaim claim{runfolder::kMapProgram, req.input_path, source->describe(), "",
                               {req.config_path, req.times_path, req.can_log_path, req.vehicle_ini_path, req.gnss_path,
                                req.prior_map_dir},
                               req.force};
  const auto forced = runfolder::claimOutputFolder(req.out_dir, claim);
  writeFileAtomically(req.out_dir + "/config_used.ini", params.used());

  const bool localize = stages.prior_map.has_value();
  stages.maps = req.maps;
  if (req.export_sweeps) stages.sweep_export_dir = req.out_dir + "/sweeps";
  if (!req.can_log_path.empty()) stages.can = std::make_unique<pipeline::CanPriorStream>(req.can_log_path, req.vehicle_ini_path, *cfg);
  pipeline::Pipeline pipe(std::move(source), pipeline::buildStages(params.chain, std::move(stages)));
  MapOutcome out;
  Sinks sinks;
  drive(pipe, req, gnss, sinks, out);

  pipeline::MapsStage* maps = pipe.find<pipeline::MapsStage>();
  if (maps) {
    const auto T_map_kf = maps->mapper().keyframePoses();
    for (const auto& f : out.frames) out.T_map_lidar.push_back(maps->mapper().correctedPose(f, T_map_kf));
  }
  if (localize) {
    sinks.localization.bridge(out.frames);
    out.T_map_lidar = sinks.localization.T_map_lidar;
  }
  out.summary = summarize(out.frames);
  out.summary["warnings"] = nlohmann::json::array();
  for (const auto& w : unknown_keys) out.summary["warnings"].push_back(w);
  for (const auto& w : forced) out.summary["warnings"].push_back(w);
  const sources::ScanSource& stream = pipe.source();
  summarizeInput(stream, params, out);
  out.summary["input_id"] = runfolder::inputId(claim);
  const auto* odometry = dynamic_cast<const pipeline::OdometryPoses*>(&pipe.poses());
  if (const pipeline::CanPriorStream* can = odometry ? odometry->can() : nullptr) {
    out.summary["can"] = {{"input", can->describe()}, {"frames", can->framesRead()},
                          {"priors_used", can->priorsGiven()}, {"priors_missing", can->priorsMissing()},
                          {"calibration", can->calibrationJson()}};
  }
  const pipeline::StageTimes& ms = pipe.totals();
  out.summary["ms_by_stage_total"] = {{"source", ms.source}, {"odometry", ms.of("poses")}, {"maps", ms.of("maps")}};
  out.summary["write_errors"] = nlohmann::json::array();
  // The outputs smallest and most valuable first, so a full disk loses the big maps, not the trajectory.
  const auto files = mapRunFiles(out.frames, out.T_map_lidar);
  runfolder::writeMapTrajectories(req.out_dir, files);
  {  // a summary of the run beside them before the big files, should the disk fill on those
    nlohmann::json early = out.summary;
    early["complete"] = false;
    early["write_errors"].push_back("the run had not finished writing its outputs (maps, objects, GNSS) when this summary was written");
    runfolder::writeSummaryJson(req.out_dir + "/" + runfolder::kSummaryJson, early);
  }
  if (localize) {
    attempt(out, [&] { writeFileAtomically(req.out_dir + "/localization.csv", sinks.localization.csv); });
    const auto* loc = pipe.find<pipeline::LocalizationStage>();
    out.summary["localization"] = sinks.localization.summary(req.prior_map_dir, loc->localizer().mapPoints());
  }
  if (auto* objects = pipe.find<pipeline::ObjectTrackingStage>()) {
    out.summary["ms_by_stage_total"]["objects"] = ms.of("objects") + ms.of("dynamic_removal");
    out.summary["ms_by_stage_total"]["deskew"] = ms.of("deskew");
    out.summary["objects"] = sinks.objects.summary(objects->objects());
    attempt(out, [&] { sinks.objects.write(req.out_dir); });
  }
  if (const auto* e = pipe.find<pipeline::SweepExportStage>()) out.summary["sweeps_exported"] = e->written();
  gnss.take(pipe.source());
  std::vector<double> gnss_stamps;
  mapping::PoseVector T_enu;
  attempt(out, [&] { T_enu = writeGnss(req, params, stream, gnss, out, gnss_stamps); });
  if (maps) attempt(out, [&] { writeMapsStage(req, params, *maps, sinks, ms, out); });
  if (maps && !T_enu.empty()) {
    attempt(out, [&] {
      out.summary["gnss"]["enu_maps"] = writeEnuMaps(req.out_dir, maps->mapper().keyframes(), gnss_stamps, T_enu, params.chain.maps);
    });
  }
  out.summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!out.summary["write_errors"].empty()) out.summary["complete"] = false;
  attempt(out, [&] { runfolder::writeMapRunEnd(req.out_dir, out.summary); });
  return out;
}

}  // namespace roadslam::jobs

#include "roadslam/jobs/map_job.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "map_job_params.h"
#include "map_sinks.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/progress.h"
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
#include "roadslam/sources/scan_source.h"

namespace fs = std::filesystem;

namespace roadslam::jobs {
namespace {

void prepareOutDir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw std::runtime_error("cannot create output folder '" + dir + "': " + ec.message());
  }
  // probe: fail before hours of processing, not after
  writeFileAtomically(dir + "/.write_test", "");
  fs::remove(dir + "/.write_test");
}

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

/// The GNSS the request asks to fuse: an NMEA log (read before the run: a bad log fails before hours
/// of processing), or the GPS source of the input chosen by label; their fixes are taken per sweep.
struct GnssRequest {
  std::optional<GnssInput> input;
  bool from_input = false;
  std::string label;
  std::vector<gnss::GnssFix> fixes;

  GnssRequest(const MapRequest& req, const gnss_fusion::GnssFusionParams& p) : from_input(req.gnss_from_input) {
    if (!req.gnss_path.empty() && req.gnss_from_input) throw std::runtime_error("--gnss and --gnss-from-input exclude each other");
    if (!req.gnss_path.empty()) input = readGnssInput(req.gnss_path, p);
    if (!req.gnss_label.empty() && !req.gnss_from_input) throw std::runtime_error("--gnss-label needs --gnss-from-input");
    if (req.gnss_from_input) label = chooseGpsSource(sources::gpsSourcesOf(req.input_path), req.gnss_label, req.input_path);
  }
  void take(sources::ScanSource& src) {
    if (from_input) keepFixes(src.takeGpsFixes(), label, fixes);
  }
};

/// What the job collects from the pipeline's frames.
struct Sinks {
  ObjectsOutput objects;
  LocalizationOutput localization;
};

/// The pipeline's frames into \p out and the sinks until the source ends, the request's limit or a stop.
void drive(pipeline::Pipeline& pipe, const MapRequest& req, GnssRequest& gnss, Sinks& sinks, MapOutcome& out) {
  pipeline::ObjectTrackingStage* objects = pipe.find<pipeline::ObjectTrackingStage>();
  const bool localize = pipe.find<pipeline::LocalizationStage>() != nullptr;
  ProgressBar bar("roadslam-map", pipe.source().sizeHint());
  while (!stopRequested()) {
    if (req.max_frames && out.frames.size() >= req.max_frames) break;
    auto f = pipe.next();
    if (!f) break;
    gnss.take(pipe.source());
    if (objects) sinks.objects.add(*f, objects->objects());
    if (localize) sinks.localization.add(*f);
    out.frames.push_back(std::move(*f->pose.odometry));
    if (req.progress) bar.update(out.frames.size());
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

/// GNSS fusion of the trajectory (batch, and the online mode replayed) and its outputs.
void writeGnss(const MapRequest& req, const MapJobParams& params, const sources::ScanSource& stream,
               GnssRequest& gnss, const pipeline::MapsStage* maps, MapOutcome& out) {
  if (gnss.from_input) {
    try {
      gnss.input = gnssInputFromFixes(gnss.fixes, "GPS fixes of " + stream.describe() + " (" + gnss.label + ")",
                                      params.gnss_fusion);
    } catch (const std::exception& e) {
      out.summary["warnings"].push_back(std::string("GNSS fusion not done: ") + e.what());
    }
  }
  if (!gnss.input) return;
  std::vector<double> stamps;
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
  if (maps && !T_enu.empty())
    out.summary["gnss"]["enu_maps"] = writeEnuMaps(req.out_dir, maps->mapper().keyframes(), stamps, T_enu, params.chain.maps);
  out.summary["gnss"]["online"] = writeOnlineGnss(req.out_dir, stamps, T_odom, *gnss.input, params.gnss_fusion);
  const auto& g = out.summary["gnss"];
  if (g["status"] != "ok") out.summary["warnings"].push_back("GNSS fusion not done: " + g["status"].get<std::string>());
  for (const auto& [name, n] : gnss.input->log.counters.named()) {
    if (n > 0 && name != "lines" && name != "sentences" && name != "epochs" && name != "fixes" && name != "unsupported sentence")
      out.summary["warnings"].push_back("GNSS log: " + std::to_string(n) + " x " + name);
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
  auto source = pipeline::openNonEmptySource(req.input_path, *cfg, req.times_path);
  GnssRequest gnss(req, params.gnss_fusion);
  prepareOutDir(req.out_dir);
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
    writeFileAtomically(req.out_dir + "/localization.csv", sinks.localization.csv);
  }
  out.summary = summarize(out.frames);
  out.summary["warnings"] = nlohmann::json::array();
  for (const auto& w : unknown_keys) out.summary["warnings"].push_back(w);
  const sources::ScanSource& stream = pipe.source();
  summarizeInput(stream, params, out);
  const auto* odometry = dynamic_cast<const pipeline::OdometryPoses*>(&pipe.poses());
  if (const pipeline::CanPriorStream* can = odometry ? odometry->can() : nullptr) {
    out.summary["can"] = {{"input", can->describe()}, {"frames", can->framesRead()},
                          {"priors_used", can->priorsGiven()}, {"priors_missing", can->priorsMissing()},
                          {"calibration", can->calibrationJson()}};
  }
  const pipeline::StageTimes& ms = pipe.totals();
  out.summary["ms_by_stage_total"] = {{"source", ms.source}, {"odometry", ms.of("poses")}, {"maps", ms.of("maps")}};
  if (auto* objects = pipe.find<pipeline::ObjectTrackingStage>()) {
    out.summary["ms_by_stage_total"]["objects"] = ms.of("objects") + ms.of("dynamic_removal");
    out.summary["ms_by_stage_total"]["deskew"] = ms.of("deskew");
    out.summary["objects"] = sinks.objects.summary(objects->objects());
    sinks.objects.write(req.out_dir);
  }
  if (localize) {
    const auto* loc = pipe.find<pipeline::LocalizationStage>();
    out.summary["localization"] = sinks.localization.summary(req.prior_map_dir, loc->localizer().mapPoints());
  }
  if (const auto* e = pipe.find<pipeline::SweepExportStage>()) out.summary["sweeps_exported"] = e->written();
  if (maps) writeMapsStage(req, params, *maps, sinks, ms, out);
  gnss.take(pipe.source());
  writeGnss(req, params, stream, gnss, maps, out);
  out.summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeMapOutputs(req.out_dir, out.frames, out.T_map_lidar, out.summary);
  return out;
}

}  // namespace roadslam::jobs

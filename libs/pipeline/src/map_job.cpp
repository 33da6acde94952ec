#include "roadslam/pipeline/map_job.h"

#include "roadslam/mapping/localizer.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/progress.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/datasets/kitti_scans.h"
#include "roadslam/pipeline/vehicle_prior.h"
#include "roadslam/mapping/map_outputs.h"
#include "roadslam/mapping/mapper.h"
#include "roadslam/objects/stage.h"
#include "roadslam/pipeline/can_prior.h"
#include "roadslam/pipeline/gnss_outputs.h"
#include "roadslam/pipeline/pipeline.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/velodyne/decoder_params.h"

namespace fs = std::filesystem;

namespace roadslam::pipeline {
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

struct JobParams {
  odometry::Params odometry;
  velodyne::DecoderParams decoder;
  datasets::KittiParams kitti;
  pipeline::VehiclePriorParams vehicle_prior;  ///< read by CanPriorStream with --can; recorded always
  mapping::MapperParams mapper;
  mapping::MapOutputParams maps;
  objects::ClusterParams objects;    ///< [objects] (ground labels from [preprocess] seg_*)
  objects::TrackerParams tracking;   ///< [tracking]
  mapping::GnssFusionParams gnss_fusion;  ///< [gnss_fusion], read by --gnss; recorded always
  mapping::LocalizerParams localizer;  ///< [localization] (--prior-map); its global registration: [loop_closure_global]

  void load(const mrpt::config::CConfigFileBase& cfg) {
    objects.loadFromConfigFile(cfg, "objects", "preprocess");
    tracking.loadFromConfigFile(cfg, "tracking");
    odometry.loadFromConfigFile(cfg);
    decoder.loadFromConfigFile(cfg, "velodyne");
    kitti.loadFromConfigFile(cfg, "kitti");
    vehicle_prior.loadFromConfigFile(cfg, "vehicle_prior");
    mapper.loadFromConfigFile(cfg);
    maps.loadFromConfigFile(cfg);
    gnss_fusion.loadFromConfigFile(cfg, "gnss_fusion");
    localizer.loadFromConfigFile(cfg);
    localizer.global = mapper.loop.global;
  }
  std::string used() const {
    mrpt::config::CConfigFileMemory out;
    odometry.saveToConfigFile(out);
    decoder.saveToConfigFile(out, "velodyne");
    kitti.saveToConfigFile(out, "kitti");
    vehicle_prior.saveToConfigFile(out, "vehicle_prior");
    mapper.saveToConfigFile(out);
    maps.saveToConfigFile(out);
    objects.saveToConfigFile(out, "objects");
    tracking.saveToConfigFile(out, "tracking");
    gnss_fusion.saveToConfigFile(out, "gnss_fusion");
    localizer.saveToConfigFile(out);
    return out.getContent();
  }
};

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

/// objects.csv, tracks.csv and tracks_ended.csv as the sweeps come, and the stage's figures.
struct ObjectsOutput {
  std::string objects = objects::objectsCsvHeader(), tracks = objects::tracksCsvHeader(),
              ended = objects::endedCsvHeader();
  std::vector<double> ms;  ///< per sweep with a pose: segmentation + tracking [ms]
  std::vector<double> ms_ground;
  size_t n_objects = 0;
  size_t moving_points_removed = 0;
  size_t retro_points_removed = 0;  ///< from earlier keyframes, when their track was labelled moving
  size_t odometry_points_excluded = 0;  ///< kept out of the odometry's local map (remove_moving_from_odometry)
  std::map<std::string, int> end_reasons;
  std::map<int, mapping::TopViewBox> last_moving;  ///< each moving track's last box, for map_top.png

  void add(const PipelineFrame& f, objects::ObjectsStage& stage) {
    if (!f.objects) return;
    moving_points_removed += f.moving_points_removed;
    retro_points_removed += f.retro_points_removed;
    if (f.pose.odometry) odometry_points_excluded += static_cast<size_t>(f.pose.odometry->map_points_excluded);
    const objects::ObjectsFrame& o = *f.objects;
    const double t = f.pose.ok ? f.pose.t_ref : f.pose.stamp_s;  // the time the tracks are at
    if (f.pose.ok) {
      objects += objects::objectsCsvRows(f.index, t, f.pose.ref, o);
      ms.push_back(o.ms_segment + o.ms_track);
      ms_ground.push_back(o.ms_ground);
      n_objects += o.objects.size();
    }
    tracks += objects::tracksCsvRows(f.index, t, o);
    for (const objects::Track& tr : o.tracks) {
      if (tr.moving) last_moving[tr.id] = {tr.id, tr.x.head<2>(), tr.heading, tr.length, tr.width, tr.x.tail<2>()};
    }
    take(stage);
  }
  void take(objects::ObjectsStage& stage) {
    const auto e = stage.tracker().takeEnded();
    for (const auto& t : e) end_reasons[t.reason]++;
    ended += objects::endedCsvRows(e);
  }
  nlohmann::json summary(const objects::ObjectsStage& stage) const {
    auto stats = [](std::vector<double> v) {
      if (v.empty()) return nlohmann::json{{"mean", 0}, {"p95", 0}, {"max", 0}};
      double sum = 0;
      for (double x : v) sum += x;
      std::sort(v.begin(), v.end());
      return nlohmann::json{{"mean", sum / v.size()}, {"p95", v[std::min(v.size() - 1, v.size() * 95 / 100)]},
                            {"max", v.back()}};
    };
    int confirmed_alive = 0;
    for (const auto& t : stage.tracker().tracks()) confirmed_alive += t.state == objects::TrackState::Confirmed;
    return {{"objects", n_objects}, {"tracks_alive_at_end", confirmed_alive}, {"moving_points_removed_from_maps", moving_points_removed},
            {"earlier_points_removed_from_keyframes", retro_points_removed},
            {"moving_points_kept_out_of_odometry_map", odometry_points_excluded}, {"tracks_ended", end_reasons},
            {"tracks_reidentified", stage.tracker().reidentified()},
            {"ms_segment_track_per_frame", stats(ms)}, {"ms_ground_per_frame", stats(ms_ground)}};
  }
};

}  // namespace

std::string effectiveMapConfig(const mrpt::config::CConfigFileBase& cfg) {
  JobParams params;
  params.load(cfg);
  return params.used();
}

namespace {

/// Localization in a prior map, one row per sweep (localization.csv) and the poses in the map's frame.
struct PriorMapRun {
  std::unique_ptr<mapping::Localizer> localizer;
  std::vector<int> localized;  ///< per frame: 1 when the localizer gave its pose
  std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> T_map_lidar;
  std::string csv = "frame,stamp_s,status,confidence,keyframe,weak_directions,reason\n";
  int tracked = 0, relocalized = 0, lost = 0;
  double sum_conf = 0;

  void add(size_t index, double stamp_s, const SweepPose& pose) {
    mapping::LocalizationResult r;
    if (pose.ok && pose.points_lidar) r = localizer->localize(*pose.points_lidar);
    else r.reason = pose.ok ? "no points" : "no odometry pose: " + pose.why;
    localized.push_back(r.status != mapping::LocalizationStatus::Lost ? 1 : 0);
    T_map_lidar.push_back(r.T_map_lidar);
    tracked += r.status == mapping::LocalizationStatus::Tracked;
    relocalized += r.status == mapping::LocalizationStatus::Relocalized;
    lost += r.status == mapping::LocalizationStatus::Lost;
    sum_conf += r.confidence;
    std::string why = r.reason;
    for (char& c : why) c = c == ',' ? ';' : c;
    csv += std::to_string(index) + "," + std::to_string(stamp_s) + "," + mapping::toString(r.status) + "," +
           std::to_string(r.confidence) + "," + std::to_string(r.keyframe) + "," + std::to_string(r.weak_directions) +
           "," + why + "\n";
  }
  /// Sweeps without a localization take the nearest localized sweep's pose moved by the odometry
  /// between them (the previous one, else the next); none localized: the odometry's own poses.
  void bridge(const std::vector<odometry::FrameResult>& frames) {
    const size_t n = std::min(frames.size(), T_map_lidar.size());
    long prev = -1;
    std::vector<long> next(n, -1);
    for (long i = static_cast<long>(n) - 1, nx = -1; i >= 0; --i) {
      if (localized[static_cast<size_t>(i)]) nx = i;
      next[static_cast<size_t>(i)] = nx;
    }
    for (size_t i = 0; i < n; ++i) {
      if (localized[i]) {
        prev = static_cast<long>(i);
        continue;
      }
      const long k = prev >= 0 ? prev : next[i];
      if (k < 0) {
        T_map_lidar[i] = frames[i].T_world_lidar;
        continue;
      }
      const auto ku = static_cast<size_t>(k);
      T_map_lidar[i] = T_map_lidar[ku] * frames[ku].T_world_lidar.inverse() * frames[i].T_world_lidar;
    }
    T_map_lidar.resize(frames.size(), Eigen::Isometry3d::Identity());
  }
  nlohmann::json summary(const std::string& dir) const {
    const int n = tracked + relocalized + lost;
    return {{"prior_map", dir}, {"map_points", localizer->mapPoints()}, {"tracked", tracked},
            {"relocalized", relocalized}, {"lost", lost}, {"mean_confidence", n > 0 ? sum_conf / n : 0.0}};
  }
};

/// Appends the fixes of the GPS source \p label to \p kept.
void keepFixes(const std::vector<sources::TimedGpsFix>& fixes, const std::string& label,
               std::vector<sources::TimedGpsFix>& kept) {
  for (const auto& f : fixes)
    if (f.label == label) kept.push_back(f);
}

}  // namespace

MapOutcome runMapJob(const MapRequest& req) {
  const auto cfg = loadIniFile(req.config_path);
  JobParams params;
  params.load(*cfg);
  const auto unknown_keys = cfg->checkEntries(req.allow_unknown_keys);
  if (!req.can_log_path.empty() && req.vehicle_ini_path.empty()) throw std::runtime_error("--can needs --vehicle (the car's vehicle ini)");
  PriorMapRun prior;
  const bool localize = !req.prior_map_dir.empty();
  if (localize) prior.localizer = std::make_unique<mapping::Localizer>(mapping::readMapFolder(req.prior_map_dir), params.localizer);
  const bool maps = req.maps && !localize;  // a prior map is never grown
  auto source = openNonEmptySource(req.input_path, *cfg, req.times_path);
  std::optional<GnssInput> gnss_in;  // read before the run: a bad log fails before hours of processing
  if (!req.gnss_path.empty() && req.gnss_from_input) throw std::runtime_error("--gnss and --gnss-from-input exclude each other");
  if (!req.gnss_path.empty()) gnss_in = readGnssInput(req.gnss_path, params.gnss_fusion);
  if (!req.gnss_label.empty() && !req.gnss_from_input) throw std::runtime_error("--gnss-label needs --gnss-from-input");
  std::string gps_label;  // with gnss_from_input: the one GPS source fused
  if (req.gnss_from_input) gps_label = chooseGpsSource(sources::gpsSourcesOf(req.input_path), req.gnss_label, req.input_path);
  std::vector<sources::TimedGpsFix> input_fixes;  // with gnss_from_input: taken from the source per sweep
  prepareOutDir(req.out_dir);
  writeFileAtomically(req.out_dir + "/config_used.ini", params.used());

  MapOutcome out;
  mapping::Mapper mapper(params.mapper);
  std::unique_ptr<mapping::OctoMapWorker> octo;
  // the seen-through pass changes the keyframes after the run: the OctoMap is then built from them at the end
  if (maps && params.maps.octomap.enabled && !params.maps.seen_through.enabled) {
    octo = std::make_unique<mapping::OctoMapWorker>(params.maps.octomap);
  }
  std::unique_ptr<CanPriorStream> can;
  if (!req.can_log_path.empty()) can = std::make_unique<CanPriorStream>(req.can_log_path, req.vehicle_ini_path, *cfg);
  Stages stages;
  std::unique_ptr<objects::ObjectsStage> objects_stage;
  if (params.objects.enabled) objects_stage = std::make_unique<objects::ObjectsStage>(params.objects, params.tracking);
  ObjectsOutput objects_out;
  // the objects stage reads the sweep after the odometry: the odometry must leave it untouched
  auto odometry = std::make_unique<OdometryPoses>(params.odometry, std::move(can), objects_stage != nullptr);
  const OdometryPoses& odo = *odometry;
  stages.poses = std::move(odometry);
  if (maps) stages.mapper = &mapper;
  stages.octomap = octo.get();
  stages.octomap_keyframe_spacing_m = params.maps.octomap.keyframe_spacing_m;
  stages.objects = objects_stage.get();
  stages.remove_moving_from_maps = params.objects.remove_moving_from_maps;
  stages.removal_margin_m = params.objects.removal_margin_m;
  stages.remove_moving_from_odometry = params.objects.enabled && params.objects.remove_moving_from_odometry;
  stages.odometry_erase_back_s = params.objects.odometry_erase_back_s;
  if (params.objects.enabled && params.objects.remove_moving_from_maps) stages.octomap_delay_s = params.objects.map_delay_s;
  Pipeline pipe(std::move(source), std::move(stages));
  const sources::ScanSource* stream = &pipe.source();
  ProgressBar bar("roadslam-map", stream->sizeHint());
  const auto t0 = std::chrono::steady_clock::now();
  while (!stopRequested()) {
    if (req.max_frames && out.frames.size() >= req.max_frames) break;
    auto f = pipe.next();
    if (!f) break;
    if (req.gnss_from_input) keepFixes(pipe.source().takeGpsFixes(), gps_label, input_fixes);
    if (objects_stage) objects_out.add(*f, *objects_stage);
    if (localize) prior.add(f->index, f->pose.stamp_s, f->pose);
    out.frames.push_back(std::move(*f->pose.odometry));
    if (req.progress) bar.update(out.frames.size());
  }
  pipe.flushMaps();
  bar.finish();
  out.interrupted = stopRequested();
  if (maps) {
    const auto T_map_kf = mapper.keyframePoses();
    for (const auto& f : out.frames) out.T_map_lidar.push_back(mapper.correctedPose(f, T_map_kf));
  }
  if (localize) {
    prior.bridge(out.frames);
    out.T_map_lidar = prior.T_map_lidar;
    writeFileAtomically(req.out_dir + "/localization.csv", prior.csv);
  }
  out.summary = summarize(out.frames);
  out.summary["warnings"] = nlohmann::json::array();
  for (const auto& w : unknown_keys) out.summary["warnings"].push_back(w);
  const std::string damage = stream->errorMessage();
  if (!damage.empty()) {
    out.summary["warnings"].push_back("input damaged, " + std::to_string(stream->stats().sweeps) +
                                      " sweeps read before it: " + damage);
  }
  out.summary["complete"] = damage.empty() && !out.interrupted;
  for (const auto& w : stream->warnings()) out.summary["warnings"].push_back(w);
  const int timed = out.summary["deskewed_frames"].get<int>();
  const int posed = static_cast<int>(out.frames.size()) - out.summary["frames_by_status"].value("skipped", 0);
  if (params.odometry.deskew && timed < posed) {
    out.summary["warnings"].push_back("deskew = true, but " + std::to_string(posed - timed) + " of " +
                                      std::to_string(posed) + " sweeps carry no point times and were not deskewed "
                                      "(set [odometry] times_from_azimuth or the source's [kitti] times_from_azimuth)");
  }
  const auto st = stream->stats();
  out.summary["input"] = stream->describe();
  out.summary["packets"] = st.packets;
  out.summary["malformed_packets"] = st.malformed_packets;
  out.summary["partial_sweeps"] = st.partial_sweeps;
  out.summary["interrupted"] = out.interrupted;
  if (const CanPriorStream* can = odo.can()) {
    out.summary["can"] = {{"input", can->describe()}, {"frames", can->framesRead()},
                          {"priors_used", can->priorsGiven()}, {"priors_missing", can->priorsMissing()},
                          {"calibration", can->calibrationJson()}};
  }
  const StageTimes& ms_stages = pipe.totals();
  out.summary["ms_by_stage_total"] = {{"source", ms_stages.source}, {"odometry", ms_stages.poses}, {"maps", ms_stages.maps}};
  if (objects_stage) {
    out.summary["ms_by_stage_total"]["objects"] = ms_stages.objects;
    out.summary["ms_by_stage_total"]["deskew"] = ms_stages.deskew;
    out.summary["objects"] = objects_out.summary(*objects_stage);
    writeFileAtomically(req.out_dir + "/objects.csv", objects_out.objects);
    writeFileAtomically(req.out_dir + "/tracks.csv", objects_out.tracks);
    writeFileAtomically(req.out_dir + "/tracks_ended.csv", objects_out.ended);
  }
  if (localize) out.summary["localization"] = prior.summary(req.prior_map_dir);
  if (maps) {
    const auto loops = loopsJson(mapper);
    out.summary["loop_closures"] = loops["accepted"].size();
    out.summary["loop_candidates_rejected"] = loops["rejected"].size();
    out.summary["loops"] = loops;
    out.summary["can_edges"] = mapper.canEdges();
    out.summary["ms_mapping_total"] = pipe.totals().maps;
    std::vector<mapping::TopViewBox> boxes;
    for (const auto& [id, b] : objects_out.last_moving) boxes.push_back(b);
    if (params.maps.seen_through.enabled) {
      const auto st = mapping::removeSeenThrough(mapper, params.maps.point_map.voxel_m, params.maps.seen_through);
      out.summary["seen_through"] = {{"voxels", st.voxels}, {"tested_voxels", st.tested_voxels},
                                     {"references", st.references}, {"dynamic_voxels", st.dynamic_voxels},
                                     {"removed_points", st.removed_points}, {"ms", st.ms}};
    }
    const auto ms = mapping::writeMaps(req.out_dir, mapper, {out.T_map_lidar.begin(), out.T_map_lidar.end()},
                                       params.maps, octo.get(), boxes);
    out.summary["maps"] = {{"points", ms.points}, {"octomap_keyframes", ms.octomap_keyframes},
                           {"octomap_leafs", ms.octomap_leafs}, {"octomap_ms_per_keyframe", ms.octomap_ms_per_keyframe},
                           {"grid_occupied_cells", ms.grid_occupied}, {"grid_free_cells", ms.grid_free},
                           {"ms_total", ms.ms_total}};
  }
  if (req.gnss_from_input) {
    keepFixes(pipe.source().takeGpsFixes(), gps_label, input_fixes);
    try {
      gnss_in = gnssInputFromFixes(input_fixes, "GPS fixes of " + stream->describe() + " (" + gps_label + ")",
                                   params.gnss_fusion);
    } catch (const std::exception& e) {
      out.summary["warnings"].push_back(std::string("GNSS fusion not done: ") + e.what());
    }
  }
  if (gnss_in) {
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
    out.summary["gnss"] = fuseAndWriteGnss(req.out_dir, stamps, T, *gnss_in, params.gnss_fusion, &T_enu);
    if (maps && !T_enu.empty())
      out.summary["gnss"]["enu_maps"] = writeEnuMaps(req.out_dir, mapper.keyframes(), stamps, T_enu, params.maps);
    out.summary["gnss"]["online"] = writeOnlineGnss(req.out_dir, stamps, T_odom, *gnss_in, params.gnss_fusion);
    const auto& g = out.summary["gnss"];
    if (g["status"] != "ok") out.summary["warnings"].push_back("GNSS fusion not done: " + g["status"].get<std::string>());
    for (const auto& [name, n] : gnss_in->log.counters.named()) {
      if (n > 0 && name != "lines" && name != "sentences" && name != "epochs" && name != "fixes" && name != "unsupported sentence")
        out.summary["warnings"].push_back("GNSS log: " + std::to_string(n) + " x " + name);
    }
  }
  out.summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeMapOutputs(req.out_dir, out.frames, out.T_map_lidar, out.summary);
  return out;
}

}  // namespace roadslam::pipeline

#include "roadslam/pipeline/map_job.h"

#include <mrpt/config/CConfigFileMemory.h>

#include <chrono>
#include <filesystem>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/progress.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/pipeline/scan_stream.h"
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

std::string usedConfig(const odometry::Params& p, const velodyne::DecoderParams& dp) {
  mrpt::config::CConfigFileMemory out;
  p.saveToConfigFile(out);
  dp.saveToConfigFile(out, "velodyne");
  return out.getContent();
}

}  // namespace

MapOutcome runMapJob(const MapRequest& req) {
  const auto cfg = loadIniFile(req.config_path);
  odometry::Params params;
  params.loadFromConfigFile(*cfg);
  velodyne::DecoderParams dp;
  dp.loadFromConfigFile(*cfg, "velodyne");
  prepareOutDir(req.out_dir);
  writeFileAtomically(req.out_dir + "/config_used.ini", usedConfig(params, dp));
  auto stream = openScanStream(req.input_path, *cfg);

  MapOutcome out;
  odometry::Odometry odo(params);
  ProgressBar bar("roadslam-map", stream->sizeHint());
  const auto t0 = std::chrono::steady_clock::now();
  while (!stopRequested()) {
    if (req.max_frames && out.frames.size() >= req.max_frames) break;
    auto scan = stream->next();
    if (!scan) break;
    out.frames.push_back(odo.process(std::move(*scan)));
    if (req.progress) bar.update(out.frames.size());
  }
  bar.finish();
  out.interrupted = stopRequested();
  out.summary = summarize(out.frames);
  const auto st = stream->stats();
  out.summary["input"] = stream->describe();
  out.summary["packets"] = st.packets;
  out.summary["malformed_packets"] = st.malformed_packets;
  out.summary["partial_sweeps"] = st.partial_sweeps;
  out.summary["interrupted"] = out.interrupted;
  out.summary["wall_time_s"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  writeMapOutputs(req.out_dir, out.frames, out.summary);
  return out;
}

}  // namespace roadslam::pipeline

#include "roadslam/viewer/recording_open.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/serialization/CArchive.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/rawlog/mrpt_stamp.h"
#include "roadslam/rawlog/rawlog_session.h"
#include "roadslam/sources/recording.h"
#include "roadslam/sources/scan_source.h"

namespace roadslam::viewer {
namespace fs = std::filesystem;

namespace {

enum class Kind { AsItIs, Pcap, Kitti };

Kind kindOf(const std::string& path) {
  if (fs::is_directory(path)) return rawlog::RawlogSession::segmentsOf(path).empty() ? Kind::Kitti : Kind::AsItIs;
  const std::string ext = fs::path(path).extension().string();
  return ext == ".pcap" || ext == ".pcapng" ? Kind::Pcap : Kind::AsItIs;
}

/// A KITTI folder of NNNNNN.bin sweeps as an MRPT rawlog \p out of CObservationPointCloud (x, y, z,
/// intensity; stamped as datasets::KittiParams times them: times.txt, else the nominal rate).
/// Returns the folder's damage (an unreadable .bin is skipped); throws when no sweep is readable.
std::string kittiToRawlog(const std::string& folder, const std::string& out) {
  mrpt::config::CConfigFileMemory no_ini;
  auto src = sources::openScanSource(folder, no_ini);
  mrpt::io::CFileGZOutputStream f(out);
  if (!f.fileOpenCorrectly()) throw std::runtime_error("cannot write '" + out + "'");
  auto ar = mrpt::serialization::archiveFrom(f);
  while (auto scan = src->next()) {
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    obs->sensorLabel = "KITTI";
    obs->timestamp = rawlog::stampOf(scan->stamp_s);  // the first sweep may be before 0.0: mrpt_stamp.h
    auto pts = mrpt::maps::CPointsMapXYZI::Create();
    pts->reserve(scan->points.size());
    for (const auto& q : scan->points) {
      pts->insertPointFast(q.x, q.y, q.z);
      pts->setPointIntensity(pts->size() - 1, q.intensity);
    }
    obs->pointcloud = pts;
    ar << *obs;
  }
  if (src->stats().sweeps == 0) throw std::runtime_error("KITTI folder '" + folder + "' holds no readable sweep: " + src->errorMessage());
  return sources::damageWarning(*src);
}

/// A Velodyne pcap as the rawlog \p out (and its "<out>.ini"); returns the pcap's damage.
std::string pcapToRawlog(const std::string& pcap, const std::string& out) {
  // The model's warning, if any, comes with the summary line (ViewerModel::lidarModel), once.
  const auto s = sources::convertToRawlog(pcap, out, {}, {}, "roadslam-rawlog convert --model");
  if (s.observations == 0) throw std::runtime_error("'" + pcap + "' holds no Velodyne sweep");
  return s.damage;
}

std::string fileText(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

/// Converts \p path into the cache unless a conversion of this version of it is there. Converts into
/// "<out>.part-PID" and renames, so a conversion cut short is never taken for a whole one.
RecordingToOpen convertOnce(const std::string& path, Kind kind, RecordingCache& cache, std::ostream& err) {
  const std::string out = cache.fileFor(path, ".rawlog"), damage_file = out + ".damage";
  if (fs::exists(out)) return {out, fileText(damage_file)};
  err << "roadslam-view: converting " << (kind == Kind::Kitti ? "the KITTI folder " : "") << path << " into " << out
      << (cache.persistent() ? " once" : " (removed at exit)") << " ...\n";
  const std::string part = out + ".part-" + std::to_string(::getpid());
  std::error_code ec;
  try {
    const std::string damage = kind == Kind::Kitti ? kittiToRawlog(path, part) : pcapToRawlog(path, part);
    if (!damage.empty()) writeFileAtomically(damage_file, damage);
    else fs::remove(damage_file, ec);  // of a conversion cut short before its rename
    fs::rename(part, out);
    if (fs::exists(part + ".ini")) fs::rename(part + ".ini", out + ".ini");
    return {out, damage};
  } catch (...) {
    fs::remove(part, ec);
    fs::remove(part + ".ini", ec);
    throw;
  }
}

}  // namespace

RecordingToOpen recordingToOpen(const std::string& path, RecordingCache& cache, std::ostream& err) {
  const Kind kind = kindOf(path);
  if (kind == Kind::AsItIs) return {path, ""};
  return convertOnce(path, kind, cache, err);
}

}  // namespace roadslam::viewer

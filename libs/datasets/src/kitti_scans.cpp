#include "roadslam/datasets/kitti_scans.h"

#include "line_parsing.h"
#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;

namespace roadslam::datasets {
namespace {
constexpr size_t kBytesPerPoint = 16;  // 4 x float32: x, y, z, reflectance (KITTI devkit readme)

bool hostIsLittleEndian() {
  const uint16_t one = 1;
  uint8_t first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}
/// Adds \p rad to each point's elevation, keeping its range and azimuth.
void raiseElevation(Scan& scan, double rad) {
  for (auto& p : scan.points) {
    const double rxy = std::hypot(p.x, p.y);
    if (rxy <= 0) continue;
    const double range = std::hypot(rxy, static_cast<double>(p.z));
    const double el = std::atan2(static_cast<double>(p.z), rxy) + rad;
    const double k = range * std::cos(el) / rxy;
    p.x = static_cast<float>(p.x * k);
    p.y = static_cast<float>(p.y * k);
    p.z = static_cast<float>(range * std::sin(el));
  }
}
}  // namespace

Scan readKittiBin(const std::string& path, double stamp_s) {
  if (!hostIsLittleEndian()) throw std::runtime_error("readKittiBin: big-endian host unsupported");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw std::runtime_error("cannot open KITTI scan '" + path + "'");
  const auto size = static_cast<size_t>(in.tellg());
  if (size % kBytesPerPoint != 0) {
    throw std::runtime_error("KITTI scan '" + path + "' has " + std::to_string(size) +
                             " bytes, not a multiple of 16 (float32 x,y,z,reflectance)");
  }
  std::vector<float> buf(size / sizeof(float));
  in.seekg(0);
  if (size > 0 && !in.read(reinterpret_cast<char*>(buf.data()), static_cast<std::streamsize>(size))) {
    throw std::runtime_error("error reading KITTI scan '" + path + "'");
  }
  Scan scan;
  scan.stamp_s = stamp_s;
  scan.has_point_times = false;
  scan.has_rings = false;
  const size_t n = size / kBytesPerPoint;
  scan.points.resize(n);
  for (size_t i = 0; i < n; ++i) {
    ScanPoint& p = scan.points[i];
    p.x = buf[4 * i];
    p.y = buf[4 * i + 1];
    p.z = buf[4 * i + 2];
    p.intensity = buf[4 * i + 3];
  }
  return scan;
}

void writeKittiBin(const std::string& path, const Scan& scan) {
  std::string bytes(scan.points.size() * kBytesPerPoint, '\0');
  for (size_t i = 0; i < scan.points.size(); ++i) {
    const auto& p = scan.points[i];
    const float rec[4] = {p.x, p.y, p.z, p.intensity};
    std::memcpy(&bytes[i * kBytesPerPoint], rec, kBytesPerPoint);
  }
  writeFileAtomically(path, bytes);
}

void KittiParams::fields(ParamTable& t) {
  t.flag("times_from_azimuth", times_from_azimuth);
  t.num("sweep_period_s", timing.period_s);
  t.choice("spin", timing.spin, spinDirectionNames());
  t.num("cut_azimuth_deg", timing.cut_azimuth_deg);
  t.choice("stamp_reference", timing.stamp_reference, stampReferenceNames());
}

// elevation_correction_deg is converted by hand beside the table: x * M_PI / 180 rounds differently
// from ParamTable::angle's x * (M_PI / 180) for the shipped 0.22, and the KITTI figures must not move.
void KittiParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& c, const std::string& s) {
  loadFields(*this, c, s);
  elevation_correction_rad = readDouble(c, s, "elevation_correction_deg", elevation_correction_rad * 180.0 / M_PI) * M_PI / 180.0;
  if (!(timing.period_s > 0)) throw std::runtime_error("[" + s + "] sweep_period_s must be positive");
}

void KittiParams::saveToConfigFile(mrpt::config::CConfigFileBase& c, const std::string& s) const {
  saveFields(*this, c, s);
  c.write(s, "elevation_correction_deg", elevation_correction_rad * 180.0 / M_PI);
}

Scan KittiScanFolder::read(size_t i) const {
  Scan scan = readKittiBin(path(i), stamp(i));
  if (params_.times_from_azimuth) timesFromAzimuth(scan, params_.timing);
  if (params_.elevation_correction_rad != 0.0) raiseElevation(scan, params_.elevation_correction_rad);
  return scan;
}

KittiScanFolder::KittiScanFolder(const std::string& folder, const std::string& times_path, KittiParams params)
    : params_(std::move(params)) {
  if (!fs::is_directory(folder)) throw std::runtime_error("KITTI folder '" + folder + "' not found");
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.is_regular_file() && e.path().extension() == ".bin") files_.push_back(e.path().string());
  }
  if (files_.empty()) throw std::runtime_error("KITTI folder '" + folder + "' holds no .bin file");
  std::sort(files_.begin(), files_.end());  // NNNNNN.bin: zero-padded, so name order = time order
  const fs::path dir = fs::absolute(folder);
  if (!times_path.empty() && !fs::is_regular_file(times_path)) {
    throw std::runtime_error("times file '" + times_path + "' not found");
  }
  times_file_ = times_path;
  for (const fs::path& cand : {dir / "times.txt", dir.parent_path() / "times.txt"}) {
    if (times_file_.empty() && fs::is_regular_file(cand)) {
      times_file_ = cand.string();
      break;
    }
  }
  if (times_file_.empty()) return;
  detail::forEachNumberLine(times_file_, [&](const std::vector<double>& v, int line_no) {
    detail::expectCount(v, 1, times_file_, line_no);
    times_s_.push_back(v[0]);
  });
  if (times_s_.size() != files_.size()) {
    throw std::runtime_error("'" + times_file_ + "' has " + std::to_string(times_s_.size()) +
                             " stamps for " + std::to_string(files_.size()) + " .bin files in '" +
                             folder + "'");
  }
}

double KittiScanFolder::stamp(size_t i) const {
  if (i >= files_.size()) throw std::out_of_range("KittiScanFolder::stamp: index out of range");
  return times_s_.empty() ? params_.timing.period_s * static_cast<double>(i) : times_s_[i];
}

std::string unpackTarZstOnce(const std::string& tar_zst, const std::string& dest_dir) {
  const fs::path marker = fs::path(dest_dir) / ".unpacked";
  if (fs::exists(marker)) return dest_dir;
  if (!fs::is_regular_file(tar_zst)) throw std::runtime_error("archive '" + tar_zst + "' not found");
  if ((tar_zst + dest_dir).find('\'') != std::string::npos) {  // the paths go into a shell command
    throw std::runtime_error("unpackTarZstOnce: quote character in '" + tar_zst + "' or '" + dest_dir + "'");
  }
  const fs::path tmp = fs::path(dest_dir).string() + ".tmp-" + std::to_string(::getpid());
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const std::string cmd = "zstd -dc -q '" + tar_zst + "' | tar -x -C '" + tmp.string() + "'";
  if (std::system(cmd.c_str()) != 0) {
    fs::remove_all(tmp);
    throw std::runtime_error("unpacking '" + tar_zst + "' failed: " + cmd);
  }
  std::ofstream(tmp / ".unpacked") << tar_zst << '\n';
  if (fs::path(dest_dir).has_parent_path()) fs::create_directories(fs::path(dest_dir).parent_path());
  std::error_code ec;
  fs::rename(tmp, dest_dir, ec);
  if (ec) {
    fs::remove_all(tmp);  // another process won the race: its complete copy is used
    if (!fs::exists(marker)) throw std::runtime_error("cannot create '" + dest_dir + "': " + ec.message());
  }
  return dest_dir;
}

}  // namespace roadslam::datasets

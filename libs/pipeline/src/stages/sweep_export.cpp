#include "roadslam/pipeline/stages/sweep_export.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::pipeline {

SweepExportStage::SweepExportStage(std::string folder) : folder_(std::move(folder)) {
  std::error_code ec;
  std::filesystem::create_directories(folder_, ec);
  if (ec || !std::filesystem::is_directory(folder_))
    throw std::runtime_error("cannot create the sweep folder '" + folder_ + "': " + ec.message());
}

void SweepExportStage::process(PipelineFrame& f) {
  if (!f.pose.ok) return;
  char name[32];
  std::snprintf(name, sizeof name, "/%06zu.pcd", f.index);
  writeSweepPcd(folder_ + name, *f.scan);
  ++written_;
}

void writeSweepPcd(const std::string& path, const Scan& scan) {
  // PCD v0.7 (pointclouds.org/documentation/tutorials/pcd_file_format.html): an ASCII header, then
  // the points packed field after field in the order of FIELDS, little-endian as the host.
  const std::string n = std::to_string(scan.points.size());
  std::string data = "# .PCD v0.7 - roadslam deskewed sweep, lidar frame at its reference time, metres\n"
                     "VERSION 0.7\nFIELDS x y z intensity ring t\nSIZE 4 4 4 4 2 4\nTYPE F F F F U F\n"
                     "COUNT 1 1 1 1 1 1\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n +
                     "\nDATA binary\n";
  constexpr size_t kPointBytes = 4 * 4 + 2 + 4;
  const size_t head = data.size();
  data.resize(head + kPointBytes * scan.points.size());
  char* out = data.data() + head;
  for (const ScanPoint& p : scan.points) {
    const float xyzi[4] = {p.x, p.y, p.z, p.intensity};
    std::memcpy(out, xyzi, sizeof xyzi);
    std::memcpy(out + 16, &p.ring, 2);
    std::memcpy(out + 18, &p.t, 4);
    out += kPointBytes;
  }
  writeFileAtomically(path, data);
}

}  // namespace roadslam::pipeline

#include <fstream>
#include <stdexcept>
#include <unordered_set>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/voxel_hash.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "ini_keys.h"
#include "roadslam/mapping/maps.h"

namespace roadslam::mapping {
namespace {

void writeBinaryFile(const std::string& path, const std::string& header, const std::vector<Eigen::Vector3f>& pts) {
  AtomicFile f(path, std::ios::out | std::ios::trunc | std::ios::binary);
  f.stream() << header;
  // x86/ARM little endian: the float bytes are the file's
  for (const auto& p : pts) f.stream().write(reinterpret_cast<const char*>(p.data()), 3 * sizeof(float));
  f.commit();
}

}  // namespace

void PointMapParams::fields(ParamTable& t) {
  t.num("voxel_m", voxel_m);
}

void PointMapParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<PointMapParams>());
  if (voxel_m <= 0) throw std::runtime_error("[" + s + "] voxel_m must be > 0");
}
void PointMapParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

std::vector<Eigen::Vector3f> buildPointMap(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, double voxel_m) {
  std::unordered_set<Eigen::Vector3i, VoxelKeyHash> seen;
  std::vector<Eigen::Vector3f> out;
  for (size_t k = 0; k < kfs.size() && k < T_map_kf.size(); ++k) {
    const Eigen::Isometry3f T = T_map_kf[k].cast<float>();
    for (const auto& q : kfs[k].points_lidar) {
      const Eigen::Vector3f p = T * q;
      if (seen.insert((p / static_cast<float>(voxel_m)).array().floor().cast<int>().matrix()).second) out.push_back(p);
    }
  }
  return out;
}

void writePly(const std::string& path, const std::vector<Eigen::Vector3f>& pts) {
  const std::string header = "ply\nformat binary_little_endian 1.0\ncomment roadslam point map, map frame, metres\n"
                             "element vertex " + std::to_string(pts.size()) +
                             "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  writeBinaryFile(path, header, pts);
}

void writePcd(const std::string& path, const std::vector<Eigen::Vector3f>& pts) {
  const std::string n = std::to_string(pts.size());
  const std::string header = "# .PCD v0.7 - roadslam point map, map frame, metres\nVERSION 0.7\nFIELDS x y z\n"
                             "SIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " + n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\n"
                             "POINTS " + n + "\nDATA binary\n";
  writeBinaryFile(path, header, pts);
}

}  // namespace roadslam::mapping

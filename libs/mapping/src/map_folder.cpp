#include "roadslam/mapping/map_folder.h"

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"

namespace roadslam::mapping {
namespace {

constexpr char kMagic[4] = {'R', 'S', 'K', 'F'};
constexpr const char* kFormat = "roadslam-map";

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

/// Reads from a byte buffer, throwing "<file>: truncated" when it runs out.
struct Reader {
  const std::string& buf;
  const std::string& file;
  size_t pos = 0;
  template <class T>
  T get() {
    if (pos + sizeof(T) > buf.size()) throw std::runtime_error(file + ": truncated at byte " + std::to_string(pos));
    T v;
    std::memcpy(&v, buf.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
};

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

void writeMapFolder(const std::string& dir, const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf,
                    const place::ScanContextParams& sc) {
  std::string bin(kMagic, 4);
  put(bin, static_cast<uint32_t>(kMapFolderVersion));
  put(bin, static_cast<uint64_t>(kfs.size()));
  for (size_t i = 0; i < kfs.size(); ++i) {
    const Keyframe& k = kfs[i];
    put(bin, static_cast<uint64_t>(k.frame_index));
    put(bin, k.stamp_s);
    put(bin, k.path_m);
    const Eigen::Matrix<double, 3, 4> M = T_map_kf.at(i).matrix().topRows<3>();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) put(bin, M(r, c));
    put(bin, static_cast<uint32_t>(k.points_lidar.size()));
    for (const auto& p : k.points_lidar) bin.append(reinterpret_cast<const char*>(p.data()), 3 * sizeof(float));
    place::ScanContext d = k.descriptor;
    if (d.bins.size() == 0) {
      std::vector<Eigen::Vector3d> pts;
      for (const auto& p : k.points_lidar) pts.push_back(p.cast<double>());
      d = place::makeScanContext(pts, sc);
    }
    put(bin, static_cast<uint32_t>(d.bins.rows()));
    put(bin, static_cast<uint32_t>(d.bins.cols()));
    for (Eigen::Index r = 0; r < d.bins.rows(); ++r)
      for (Eigen::Index c = 0; c < d.bins.cols(); ++c) put(bin, d.bins(r, c));
  }
  writeFileAtomically(dir + "/keyframes.bin", bin);
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kMapFolderVersion;
  j["keyframes"] = kfs.size();
  j["keyframes_file"] = "keyframes.bin";
  j["scan_context"] = {{"num_rings", sc.num_rings},
                       {"num_sectors", sc.num_sectors},
                       {"max_radius_m", sc.max_radius_m},
                       {"height_offset_m", sc.height_offset_m}};
  writeFileAtomically(dir + "/map.json", j.dump(2) + "\n");
}

MapFolder readMapFolder(const std::string& dir) {
  const std::string json_path = dir + "/map.json";
  if (!std::filesystem::exists(json_path)) {
    throw std::runtime_error(json_path + ": missing: " + dir +
                             " is not a roadslam map folder of version >= 1 (written by an older roadslam-map, "
                             "or by another program); run roadslam-map again to make one");
  }
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(readAll(json_path));
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(json_path + ": not valid JSON (" + e.what() + ")");
  }
  if (!j.is_object() || j.value("format", std::string()) != kFormat) {
    throw std::runtime_error(json_path + ": format is not \"" + kFormat + "\": a foreign map folder");
  }
  MapFolder m;
  m.version = j.value("version", 0);
  if (m.version != kMapFolderVersion) {
    throw std::runtime_error(json_path + ": version " + std::to_string(m.version) + ", this roadslam reads version " +
                             std::to_string(kMapFolderVersion) + "; run roadslam-map again to rebuild the folder");
  }
  try {
    const auto& s = j.at("scan_context");
    m.scan_context.num_rings = s.at("num_rings").get<int>();
    m.scan_context.num_sectors = s.at("num_sectors").get<int>();
    m.scan_context.max_radius_m = s.at("max_radius_m").get<double>();
    m.scan_context.height_offset_m = s.at("height_offset_m").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(json_path + ": " + e.what());
  }
  const std::string bin_path = dir + "/" + j.value("keyframes_file", std::string("keyframes.bin"));
  const std::string buf = readAll(bin_path);
  Reader rd{buf, bin_path};
  char magic[4];
  for (char& c : magic) c = rd.get<char>();
  if (std::memcmp(magic, kMagic, 4) != 0) throw std::runtime_error(bin_path + ": not a roadslam keyframe file (bad magic)");
  const uint32_t v = rd.get<uint32_t>();
  if (v != static_cast<uint32_t>(kMapFolderVersion))
    throw std::runtime_error(bin_path + ": version " + std::to_string(v) + ", expected " + std::to_string(kMapFolderVersion));
  const uint64_t n = rd.get<uint64_t>();
  if (n != j.value("keyframes", uint64_t{0}))
    throw std::runtime_error(bin_path + ": holds " + std::to_string(n) + " keyframes, map.json says " +
                             std::to_string(j.value("keyframes", uint64_t{0})));
  for (uint64_t i = 0; i < n; ++i) {
    Keyframe k;
    k.frame_index = static_cast<size_t>(rd.get<uint64_t>());
    k.stamp_s = rd.get<double>();
    k.path_m = rd.get<double>();
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) T.matrix()(r, c) = rd.get<double>();
    const uint32_t np = rd.get<uint32_t>();
    if (static_cast<uint64_t>(np) * 12 > buf.size() - rd.pos) throw std::runtime_error(bin_path + ": truncated in keyframe " + std::to_string(i));
    k.points_lidar.resize(np);
    for (auto& p : k.points_lidar) {
      p.x() = rd.get<float>();
      p.y() = rd.get<float>();
      p.z() = rd.get<float>();
    }
    const uint32_t rows = rd.get<uint32_t>(), cols = rd.get<uint32_t>();
    if (static_cast<int>(rows) != m.scan_context.num_rings || static_cast<int>(cols) != m.scan_context.num_sectors)
      throw std::runtime_error(bin_path + ": keyframe " + std::to_string(i) + " descriptor is " + std::to_string(rows) + "x" +
                               std::to_string(cols) + ", map.json says " + std::to_string(m.scan_context.num_rings) + "x" +
                               std::to_string(m.scan_context.num_sectors));
    k.descriptor.bins.resize(rows, cols);
    for (uint32_t r = 0; r < rows; ++r)
      for (uint32_t c = 0; c < cols; ++c) k.descriptor.bins(r, c) = rd.get<float>();
    k.descriptor.ring_key = k.descriptor.bins.rowwise().mean();
    k.T_odom_lidar = T;
    m.T_map_kf.push_back(T);
    m.keyframes.push_back(std::move(k));
  }
  if (rd.pos != buf.size()) throw std::runtime_error(bin_path + ": " + std::to_string(buf.size() - rd.pos) + " bytes after the last keyframe");
  return m;
}

}  // namespace roadslam::mapping

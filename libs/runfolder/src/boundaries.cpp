#include "roadslam/runfolder/boundaries.h"

#include <fstream>
#include <stdexcept>

namespace roadslam::runfolder {
namespace {

Eigen::Vector3d point3(const nlohmann::json& p) {
  return {p.at(0).get<double>(), p.at(1).get<double>(), p.size() > 2 ? p.at(2).get<double>() : 0.0};
}

BoundarySide side(const nlohmann::json& j) {
  BoundarySide s;
  s.found = j.at("found").get<bool>();
  s.reason = j.value("reason", "");
  s.confidence = j.value("confidence", 0.0);
  for (const auto& p : j.at("polyline_map")) s.polyline_map.push_back(point3(p));
  return s;
}

}  // namespace

std::string noPoseLine(double stamp_s, const std::string& reason) {
  return nlohmann::json{{"stamp_s", stamp_s}, {"status", "no_pose"}, {"reason", reason}}.dump() + "\n";
}

BoundaryRecord boundaryFromJson(const nlohmann::json& j, const std::string& what) {
  BoundaryRecord b;
  try {
    b.stamp_s = j.at("stamp_s").get<double>();
    b.status = j.at("status").get<std::string>();
    b.has_pose = b.status != "no_pose";
    b.reason = j.value("reason", "");
    if (b.has_pose) {
      const auto& T = j.at("T_map_lidar");
      Eigen::Matrix4d M;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) M(r, c) = T.at(static_cast<size_t>(r * 4 + c)).get<double>();
      b.T_map_lidar = Eigen::Isometry3d(M);
      b.left = side(j.at("left"));
      b.right = side(j.at("right"));
      for (const auto& p : j.at("free_space")) b.free_space.emplace_back(p.at(0).get<double>(), p.at(1).get<double>());
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(what + ": " + e.what());
  }
  b.json = j;
  return b;
}

std::vector<BoundaryRecord> readBoundariesJsonl(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read");
  std::vector<BoundaryRecord> out;
  std::string line;
  for (size_t n = 1; std::getline(f, line); ++n) {
    if (line.empty()) continue;
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(line);
    } catch (const std::exception& e) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": " + e.what());
    }
    out.push_back(boundaryFromJson(j, path + ":" + std::to_string(n)));
  }
  return out;
}

}  // namespace roadslam::runfolder

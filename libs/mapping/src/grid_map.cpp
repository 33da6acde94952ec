#include <cerrno>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "ini_keys.h"
#include "roadslam/mapping/maps.h"

namespace roadslam::mapping {

void GridParams::fields(ParamTable& t) {
  t.num("resolution_m", resolution_m);
  t.num("lidar_height_m", lidar_height_m);
  t.num("ground_tolerance_m", ground_tolerance_m);
  t.num("min_height_m", min_height_m);
  t.num("max_height_m", max_height_m);
  t.num("max_range_m", max_range_m);
  t.num("margin_m", margin_m);
}

void GridParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<GridParams>());
  if (resolution_m <= 0 || max_height_m <= min_height_m || max_range_m <= 0 || margin_m < 0) {
    throw std::runtime_error("[" + s + "]: need resolution_m > 0, max_height_m > min_height_m, max_range_m > 0");
  }
}

void GridParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

Grid2D buildGrid(const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf, const GridParams& p) {
  Grid2D g;
  g.resolution_m = p.resolution_m;
  if (kfs.empty() || T_map_kf.empty()) {  // nothing mapped (an early interruption): one unknown cell
    g.width = g.height = 1;
    g.cells.assign(1, -1);
    return g;
  }
  Eigen::Vector2d lo = T_map_kf[0].translation().head<2>(), hi = lo;
  for (const auto& T : T_map_kf) {
    lo = lo.cwiseMin(T.translation().head<2>() - Eigen::Vector2d::Constant(p.max_range_m));
    hi = hi.cwiseMax(T.translation().head<2>() + Eigen::Vector2d::Constant(p.max_range_m));
  }
  lo -= Eigen::Vector2d::Constant(p.margin_m);
  hi += Eigen::Vector2d::Constant(p.margin_m);
  g.origin_x_m = std::floor(lo.x() / p.resolution_m) * p.resolution_m;
  g.origin_y_m = std::floor(lo.y() / p.resolution_m) * p.resolution_m;
  g.width = static_cast<int>(std::ceil((hi.x() - g.origin_x_m) / p.resolution_m));
  g.height = static_cast<int>(std::ceil((hi.y() - g.origin_y_m) / p.resolution_m));
  g.cells.assign(static_cast<size_t>(g.width) * g.height, -1);
  const double r2 = p.max_range_m * p.max_range_m;
  for (size_t k = 0; k < kfs.size() && k < T_map_kf.size(); ++k) {
    const Eigen::Isometry3d& T = T_map_kf[k];
    const double ground_z = T.translation().z() - p.lidar_height_m;  // ground below this keyframe
    for (const auto& q : kfs[k].points_lidar) {
      if (q.cast<double>().head<2>().squaredNorm() > r2) continue;
      const Eigen::Vector3d pm = T * q.cast<double>();
      const int c = static_cast<int>((pm.x() - g.origin_x_m) / p.resolution_m);
      const int r = static_cast<int>((pm.y() - g.origin_y_m) / p.resolution_m);
      if (c < 0 || r < 0 || c >= g.width || r >= g.height) continue;
      const double h = pm.z() - ground_z;
      int8_t& cell = g.cells[static_cast<size_t>(r) * g.width + c];
      if (h >= p.min_height_m && h <= p.max_height_m) cell = 100;  // an obstacle wins over ground
      else if (std::abs(h) <= p.ground_tolerance_m && cell != 100) cell = 0;
    }
  }
  return g;
}

void writeGridPng(const std::string& png_path, const std::string& yaml_path, const Grid2D& g) {
  mrpt::img::CImage img(std::max(g.width, 1), std::max(g.height, 1), mrpt::img::CH_GRAY);
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const int8_t v = g.at(c, r);
      img.setPixel(c, g.height - 1 - r, v < 0 ? 205 : (v == 0 ? 254 : 0));  // map_server's colours
    }
  }
  TempFile tmp(png_path, ".png");  // the extension selects the encoder
  errno = 0;
  if (!img.saveToFile(tmp.path())) throw std::runtime_error(tmp.failure("grid image"));
  tmp.commit();
  std::ostringstream y;
  y << "# ROS map_server map: origin = map-frame pose of the lower-left pixel [m, m, rad]\n"
    << "image: " << std::filesystem::path(png_path).filename().string() << "\n"
    << "resolution: " << g.resolution_m << "\n"
    << "origin: [" << g.origin_x_m << ", " << g.origin_y_m << ", 0.0]\n"
    << "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n";
  writeFileAtomically(yaml_path, y.str());
}

void writeGridMrpt(const std::string& path, const Grid2D& g) {
  mrpt::maps::COccupancyGridMap2D m;
  const auto res = static_cast<float>(g.resolution_m);
  m.setSize(static_cast<float>(g.origin_x_m), static_cast<float>(g.origin_x_m + g.width * g.resolution_m),
            static_cast<float>(g.origin_y_m), static_cast<float>(g.origin_y_m + g.height * g.resolution_m), res, 0.5f);
  const int w = std::min<int>(g.width, static_cast<int>(m.getSizeX()));
  const int h = std::min<int>(g.height, static_cast<int>(m.getSizeY()));
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      const int8_t v = g.at(c, r);
      m.setCell(c, r, v < 0 ? 0.5f : (v == 0 ? 0.99f : 0.01f));  // MRPT cells hold p(free)
    }
  }
  TempFile tmp(path);
  try {
    mrpt::io::CFileGZOutputStream f;
    errno = 0;
    if (!f.open(tmp.path())) throw std::runtime_error("open");
    mrpt::serialization::archiveFrom(f) << m;
  } catch (const std::exception&) {
    throw std::runtime_error(tmp.failure("gridmap"));
  }
  tmp.commit();
}

}  // namespace roadslam::mapping

#include "roadslam/preprocess/crop_filters.h"

#include "param_utils.h"
#include "roadslam/common/param_table.h"

#include <algorithm>
#include <cmath>

namespace roadslam::preprocess {
namespace {
template <class Pred>
size_t eraseIf(std::vector<ScanPoint>& pts, Pred remove) {
  const size_t n = pts.size();
  pts.erase(std::remove_if(pts.begin(), pts.end(), remove), pts.end());
  return n - pts.size();
}
}  // namespace

size_t removeNonFinite(std::vector<ScanPoint>& pts) {
  return eraseIf(pts, [](const ScanPoint& p) {
    return !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  });
}

size_t removeEgo(std::vector<ScanPoint>& pts, const EgoParams& prm) {
  const float r2 = static_cast<float>(prm.radius_m * prm.radius_m);
  return eraseIf(pts, [r2](const ScanPoint& p) { return p.x * p.x + p.y * p.y < r2; });
}

size_t removeOutOfRange(std::vector<ScanPoint>& pts, const RangeParams& prm) {
  const float lo = static_cast<float>(prm.min_range_m * prm.min_range_m);
  const float hi = static_cast<float>(prm.max_range_m * prm.max_range_m);
  return eraseIf(pts, [lo, hi](const ScanPoint& p) {
    const float r2 = p.x * p.x + p.y * p.y + p.z * p.z;
    return r2 < lo || r2 > hi;
  });
}

size_t removeOutsideRoi(std::vector<ScanPoint>& pts, const RoiParams& prm) {
  const float hx = static_cast<float>(prm.half_x_m), hy = static_cast<float>(prm.half_y_m);
  const float z0 = static_cast<float>(prm.min_z_m), z1 = static_cast<float>(prm.max_z_m);
  return eraseIf(pts, [=](const ScanPoint& p) {
    return std::abs(p.x) > hx || std::abs(p.y) > hy || p.z < z0 || p.z > z1;
  });
}

void EgoParams::fields(ParamTable& t) {
  t.numOrAlias("ego_radius_m", "rad", radius_m);
}

void EgoParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(radius_m >= 0, s, "ego_radius_m", "must be >= 0");
}
void EgoParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

void RangeParams::fields(ParamTable& t) {
  t.num("min_range_m", min_range_m);
  t.num("max_range_m", max_range_m);
}

void RangeParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(min_range_m >= 0 && max_range_m > min_range_m, s, "min_range_m/max_range_m",
                  "need 0 <= min < max");
}
void RangeParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

void RoiParams::fields(ParamTable& t) {
  t.numOrAlias("roi_half_x_m", "xL", half_x_m);
  t.numOrAlias("roi_half_y_m", "yL", half_y_m);
  t.num("roi_min_z_m", min_z_m);
  t.num("roi_max_z_m", max_z_m);
}

void RoiParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(half_x_m > 0 && half_y_m > 0, s, "roi_half_x_m/roi_half_y_m", "must be > 0");
  detail::require(min_z_m < max_z_m, s, "roi_min_z_m/roi_max_z_m", "need min < max");
}
void RoiParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

}  // namespace roadslam::preprocess

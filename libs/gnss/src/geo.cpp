#include "roadslam/gnss/geo.h"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace roadslam::gnss {

std::string Utm::zoneName() const { return std::to_string(zone) + (north ? "N" : "S"); }

Eigen::Vector3d ecefFromGeodetic(const Geodetic& g) {
  Eigen::Vector3d x;
  GeographicLib::Geocentric::WGS84().Forward(g.lat_deg, g.lon_deg, g.h_m, x.x(), x.y(), x.z());
  return x;
}

Geodetic geodeticFromEcef(const Eigen::Vector3d& x) {
  Geodetic g;
  GeographicLib::Geocentric::WGS84().Reverse(x.x(), x.y(), x.z(), g.lat_deg, g.lon_deg, g.h_m);
  return g;
}

Utm utmFromGeodetic(const Geodetic& g, int zone) {
  Utm u;
  double gamma = 0, k = 0;
  try {
    GeographicLib::UTMUPS::Forward(g.lat_deg, g.lon_deg, u.zone, u.north, u.easting_m, u.northing_m, gamma, k,
                                   zone < 0 ? GeographicLib::UTMUPS::STANDARD : zone);
  } catch (const GeographicLib::GeographicErr& e) {
    throw std::invalid_argument(std::string("UTM conversion: ") + e.what());
  }
  u.h_m = g.h_m;
  u.convergence_rad = gamma * M_PI / 180;
  u.scale = k;
  return u;
}

Geodetic geodeticFromUtm(const Utm& u) {
  Geodetic g;
  try {
    GeographicLib::UTMUPS::Reverse(u.zone, u.north, u.easting_m, u.northing_m, g.lat_deg, g.lon_deg);
  } catch (const GeographicLib::GeographicErr& e) {
    throw std::invalid_argument(std::string("UTM conversion: ") + e.what());
  }
  g.h_m = u.h_m;
  return g;
}

struct EnuFrame::Impl {
  GeographicLib::LocalCartesian lc;
};

EnuFrame::EnuFrame(const Geodetic& origin)
    : origin_(origin),
      impl_(std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(origin.lat_deg, origin.lon_deg, origin.h_m,
                                                                        GeographicLib::Geocentric::WGS84())})) {}
EnuFrame::~EnuFrame() = default;
EnuFrame::EnuFrame(const EnuFrame& o) : origin_(o.origin_), impl_(std::make_unique<Impl>(*o.impl_)) {}
EnuFrame& EnuFrame::operator=(const EnuFrame& o) {
  origin_ = o.origin_;
  impl_ = std::make_unique<Impl>(*o.impl_);
  return *this;
}

Eigen::Vector3d EnuFrame::toEnu(const Geodetic& g) const {
  Eigen::Vector3d e;
  impl_->lc.Forward(g.lat_deg, g.lon_deg, g.h_m, e.x(), e.y(), e.z());
  return e;
}

Geodetic EnuFrame::toGeodetic(const Eigen::Vector3d& e) const {
  Geodetic g;
  impl_->lc.Reverse(e.x(), e.y(), e.z(), g.lat_deg, g.lon_deg, g.h_m);
  return g;
}

Eigen::Vector3d EnuFrame::enuFromEcef(const Eigen::Vector3d& ecef) const { return toEnu(geodeticFromEcef(ecef)); }

Eigen::Matrix3d EnuFrame::R_ecef_enu() const {
  // Geocentric's rotation matrix M maps local ENU to ECEF (row-major, 9 elements).
  std::vector<double> M(9);
  double X, Y, Z;
  GeographicLib::Geocentric::WGS84().Forward(origin_.lat_deg, origin_.lon_deg, origin_.h_m, X, Y, Z, M);
  Eigen::Matrix3d R;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R(r, c) = M[static_cast<size_t>(3 * r + c)];
  return R;
}

}  // namespace roadslam::gnss

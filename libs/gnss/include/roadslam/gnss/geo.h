#pragma once
/// \file geo.h
/// Geo-referencing on the WGS84 ellipsoid with GeographicLib (Karney): geodetic <-> ECEF <-> a local
/// East-North-Up frame (GeographicLib::LocalCartesian) and geodetic <-> UTM (GeographicLib::UTMUPS).
/// GeographicLib's headers stay in geo.cpp.
///
/// Frames: `ecef` (Earth-centred, Earth-fixed, x through lat 0 / lon 0, z through the north pole) [m];
/// `enu` (x east, y north, z up along the ellipsoid normal at the origin) [m]; UTM easting / northing
/// [m] in a zone (1..60) and hemisphere, heights above the WGS84 ellipsoid [m].

#include <Eigen/Core>
#include <memory>
#include <string>

namespace roadslam::gnss {

/// A WGS84 position.
struct Geodetic {
  double lat_deg = 0;  ///< latitude, north positive [deg]
  double lon_deg = 0;  ///< longitude, east positive [deg]
  double h_m = 0;      ///< height above the WGS84 ellipsoid [m]
};

/// A UTM position.
struct Utm {
  int zone = 0;          ///< 1..60 (0 = UPS, polar)
  bool north = true;     ///< hemisphere
  double easting_m = 0;  ///< [m] (false easting 500 km included)
  double northing_m = 0; ///< [m] (false northing 10,000 km in the south included)
  double h_m = 0;        ///< height above the ellipsoid [m]
  double convergence_rad = 0;  ///< meridian convergence: grid north's angle from true north, clockwise [rad]
  double scale = 1;      ///< point scale factor k of the projection here [-]
  /// "32N" style zone name.
  std::string zoneName() const;
};

/// Geodetic -> ECEF [m].
Eigen::Vector3d ecefFromGeodetic(const Geodetic& g);
/// ECEF [m] -> geodetic (exact, GeographicLib's Geocentric::Reverse).
Geodetic geodeticFromEcef(const Eigen::Vector3d& ecef);

/// Geodetic -> UTM; \p zone < 0 picks the standard zone, else forces that zone (a drive crossing a
/// zone boundary keeps the zone of its first fix). Throws std::invalid_argument outside the UTM range.
Utm utmFromGeodetic(const Geodetic& g, int zone = -1);
/// UTM -> geodetic. Throws std::invalid_argument for an invalid zone.
Geodetic geodeticFromUtm(const Utm& u);

/// A local East-North-Up frame with its origin at a WGS84 position.
class EnuFrame {
 public:
  explicit EnuFrame(const Geodetic& origin);
  ~EnuFrame();
  EnuFrame(const EnuFrame&);
  EnuFrame& operator=(const EnuFrame&);

  const Geodetic& origin() const { return origin_; }
  /// Geodetic -> ENU [m].
  Eigen::Vector3d toEnu(const Geodetic& g) const;
  /// ENU [m] -> geodetic.
  Geodetic toGeodetic(const Eigen::Vector3d& enu) const;
  /// ECEF [m] -> ENU [m].
  Eigen::Vector3d enuFromEcef(const Eigen::Vector3d& ecef) const;
  /// Rotation R_ecef_enu (columns: east, north, up in ECEF) at the origin.
  Eigen::Matrix3d R_ecef_enu() const;

 private:
  struct Impl;
  Geodetic origin_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace roadslam::gnss

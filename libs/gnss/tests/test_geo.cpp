// Geo-referencing against independent oracles: the closed-form geodetic -> ECEF formula (Hofmann-
// Wellenhof, GNSS 2008, eq. 5.11), GeographicLib's published GeoConvert example (man page GeoConvert(1):
// "33.3 44.4" is "38n 444140.54 3684706.36") and round trips within 1 mm.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/gnss/geo.h"

using namespace roadslam::gnss;

namespace {
constexpr double kA = 6378137.0, kF = 1 / 298.257223563;

Eigen::Vector3d ecefClosedForm(double lat_deg, double lon_deg, double h) {
  const double e2 = kF * (2 - kF), phi = lat_deg * M_PI / 180, lam = lon_deg * M_PI / 180;
  const double N = kA / std::sqrt(1 - e2 * std::sin(phi) * std::sin(phi));
  return {(N + h) * std::cos(phi) * std::cos(lam), (N + h) * std::cos(phi) * std::sin(lam),
          (N * (1 - e2) + h) * std::sin(phi)};
}
}  // namespace

TEST(Geo, EcefMatchesClosedFormAndRoundTrips) {
  for (const Geodetic g : {Geodetic{48.137, 11.575, 520.0}, Geodetic{-33.8688, 151.2093, 58.0},
                           Geodetic{37.7749, -122.4194, -30.0}, Geodetic{89.9, 45.0, 10.0}}) {
    const Eigen::Vector3d x = ecefFromGeodetic(g);
    EXPECT_LT((x - ecefClosedForm(g.lat_deg, g.lon_deg, g.h_m)).norm(), 1e-6);
    const Geodetic b = geodeticFromEcef(x);
    EXPECT_LT((ecefFromGeodetic(b) - x).norm(), 1e-3);
    EXPECT_NEAR(b.lat_deg, g.lat_deg, 1e-10);
    EXPECT_NEAR(b.lon_deg, g.lon_deg, 1e-10);
    EXPECT_NEAR(b.h_m, g.h_m, 1e-4);
  }
}

TEST(Geo, UtmMatchesGeoConvertPublishedExample) {
  const Utm u = utmFromGeodetic({33.3, 44.4, 0});
  EXPECT_EQ(u.zone, 38);
  EXPECT_TRUE(u.north);
  EXPECT_EQ(u.zoneName(), "38N");
  EXPECT_NEAR(u.easting_m, 444140.54, 0.006);  // published to 1 cm
  EXPECT_NEAR(u.northing_m, 3684706.36, 0.006);
  const Geodetic b = geodeticFromUtm(u);
  // 1 mm on the ground is ~9e-9 deg
  EXPECT_NEAR(b.lat_deg, 33.3, 9e-9);
  EXPECT_NEAR(b.lon_deg, 44.4, 9e-9);
}

TEST(Geo, EnuRoundTripWithinOneMillimetre) {
  const Geodetic origin{48.137, 11.575, 520.0};
  const EnuFrame enu(origin);
  EXPECT_LT(enu.toEnu(origin).norm(), 1e-9);
  // a point 1.5 km east, 2 km north, 30 m up: ENU -> geodetic -> ENU, and through ECEF and UTM
  const Eigen::Vector3d p(1500.0, 2000.0, 30.0);
  const Geodetic g = enu.toGeodetic(p);
  EXPECT_LT((enu.toEnu(g) - p).norm(), 1e-3);
  EXPECT_LT((enu.enuFromEcef(ecefFromGeodetic(g)) - p).norm(), 1e-3);
  const Utm u = utmFromGeodetic(g);
  EXPECT_EQ(u.zoneName(), "32N");
  EXPECT_LT((enu.toEnu(geodeticFromUtm(u)) - p).norm(), 1e-3);
  // ENU axes: east is +lon, north is +lat, and R_ecef_enu maps ENU offsets into ECEF ones
  EXPECT_GT(g.lon_deg, origin.lon_deg);
  EXPECT_GT(g.lat_deg, origin.lat_deg);
  const Eigen::Vector3d d = ecefFromGeodetic(g) - ecefFromGeodetic(origin);
  EXPECT_LT((enu.R_ecef_enu().transpose() * d - p).norm(), 1.0);  // curvature: < 1 m at 2.5 km
}

TEST(Geo, UtmForcedZoneAndOutOfRange) {
  const Utm u = utmFromGeodetic({48.137, 11.99, 0}, 33);  // forced into the next zone west of it
  EXPECT_EQ(u.zone, 33);
  const Geodetic b = geodeticFromUtm(u);
  EXPECT_NEAR(b.lon_deg, 11.99, 9e-9);
  EXPECT_THROW(utmFromGeodetic({95.0, 0, 0}), std::invalid_argument);
}

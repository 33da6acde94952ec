#pragma once
/// \file gnss_outputs.h
/// GNSS at the end of a map job: an NMEA log's fixes into a local ENU frame, their batch
/// fusion into the job's trajectory (gnss_fusion/gnss_fusion.h) and the geo-referenced outputs.
///
/// ENU frame: origin at the first valid fix (WGS84 lat, lon, ellipsoidal height). Files in DIR:
///   trajectory_enu.tum    fused T_enu_lidar per frame, "t x y z qx qy qz qw" (batch: every fix)
///   trajectory_enu_online.tum  the online mode's T_enu_lidar per frame (gnss_fusion_online.h: only
///                         the fixes received by then, on the odometry's own poses), same ENU frame;
///                         frames before its first solve are left out
///   trajectory_geo.csv    per frame: t, lat_deg, lon_deg, h_m (WGS84), utm_zone, easting_m, northing_m
///                         (UTM zone of the first fix for the whole drive)
///   trajectory.geojson    the fused path, a GeoJSON LineString [lon, lat, h] (RFC 7946)
///   trajectory.kml        the same path as a KML LineString (lon,lat,h)
///   gnss_fixes.csv        per fix: t, e, n, u [m in ENU], sigma_e, sigma_n [m], use (used, rejected, unmatched)
///   map_georef.json       beside the point map and grid: the ENU origin, T_enu_map (4x4), and the UTM
///                         offset of the map's origin (zone, easting, northing, h, meridian convergence,
///                         scale): a map point p [m] lies at UTM  offset + k Rot(convergence) (T_enu_map p)_en
/// and a "gnss" object in summary.json (parser counts by name, fusion counts, rms, status).

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "roadslam/gnss/geo.h"
#include "roadslam/gnss/nmea.h"
#include "roadslam/gnss_fusion/gnss_fusion.h"
#include "roadslam/gnss_fusion/gnss_fusion_online.h"
#include "roadslam/mapping/map_outputs.h"
#include "roadslam/sources/gps_fix.h"

namespace roadslam::jobs {

/// An NMEA log's valid fixes in the ENU frame at the first of them.
struct GnssInput {
  std::string path;
  gnss::NmeaLog log;
  gnss::Geodetic origin;                   ///< the ENU origin (first valid fix)
  std::vector<gnss_fusion::GnssFactor> factors;  ///< one per valid fix
};

/// Reads \p nmea_path; throws naming the file when it cannot be read or holds no valid fix.
GnssInput readGnssInput(const std::string& nmea_path, const gnss_fusion::GnssFusionParams& p);

/// The GPS source `--gnss-from-input` fuses, from \p sources (label -> GPS records, 0 = not counted:
/// sources::gpsSourcesOf(\p input)): \p wanted when given, else the one source there is; "" when
/// there is none and none is wanted (the fusion is then skipped with a warning). Throws naming the
/// sources present (with their record counts) when \p wanted is not one of them, or when there are
/// several and none is wanted: fixes of several receivers are never mixed into one fusion.
std::string chooseGpsSource(const std::map<std::string, std::size_t>& sources, const std::string& wanted,
                            const std::string& input);

/// The valid fixes an input carried (sources::ScanSource::takeGpsFixes: a Velodyne's RMC, and from a
/// rawlog every CObservationGPS with RMC or GGA: roadslam-grab's GNSS epochs, a car's CAN_GPS), in the
/// ENU frame at the first. With a GGA HDOP: sigma HDOP x uere_m horizontally, twice that up, the GGA
/// height; else sigma fallback_sigma_m horizontally and the height unknown (sigma 1 km).
/// Stamped with the fix's UTC time when p.receiver_time and it has a date, else the capture time.
/// The "log" counts epochs, fixes and "no fix" (RMC 'V', GGA quality 0). Throws when none is valid.
GnssInput gnssInputFromFixes(const std::vector<gnss::GnssFix>& fixes, const std::string& describe,
                             const gnss_fusion::GnssFusionParams& p);

/// Fuses \p in into (\p stamps_s, \p T_map_lidar), writes the files above into \p out_dir and returns
/// the summary's "gnss" object. A fusion that cannot run (too few fixes, no motion) writes nothing
/// but that object, whose "status" says why.
/// \p T_enu_lidar_out (optional) receives the fused poses (empty when the fusion could not run).
nlohmann::json fuseAndWriteGnss(const std::string& out_dir, const std::vector<double>& stamps_s,
                                const mapping::PoseVector& T_map_lidar, const GnssInput& in,
                                const gnss_fusion::GnssFusionParams& p, mapping::PoseVector* T_enu_lidar_out = nullptr);

/// The maps rebuilt at the fused poses, in the ENU frame of trajectory_enu.tum: \p out_dir/enu/map.ply,
/// map.pcd, grid.png + grid.yaml (map_server, origin in ENU metres); each keyframe placed at the fused
/// pose of its frame (by stamp along (\p stamps_s, \p T_enu_lidar)). Returns {"dir", "points",
/// "grid_occupied_cells", "grid_free_cells"}.
nlohmann::json writeEnuMaps(const std::string& out_dir, const std::vector<mapping::Keyframe>& kfs,
                            const std::vector<double>& stamps_s, const mapping::PoseVector& T_enu_lidar,
                            const mapping::MapOutputParams& p);

/// The online mode replayed over the run: \p T_map_lidar_odometry are the odometry's own poses (no
/// loop correction, which would use later frames). Writes trajectory_enu_online.tum and returns
/// {"frames", "anchored_frames", "solves", "failed_solves", "ms_per_solve", "ms_max"}.
nlohmann::json writeOnlineGnss(const std::string& out_dir, const std::vector<double>& stamps_s,
                               const mapping::PoseVector& T_map_lidar_odometry, const GnssInput& in,
                               const gnss_fusion::GnssFusionParams& p);

/// map_georef.json read back: the ENU origin and T_enu_map. Throws naming the file and the key.
struct Georef {
  gnss::Geodetic origin;
  Eigen::Isometry3d T_enu_map = Eigen::Isometry3d::Identity();
};
Georef readGeoref(const std::string& path);

/// A road boundary polyline of one sweep, in the map frame (roadslam-bounds' polyline_map).
struct GeoPolyline {
  double stamp_s = 0;
  std::string side;  ///< "left" / "right"
  double confidence = 0;
  std::vector<Eigen::Vector3d> p_map;  ///< [m]
};
/// boundaries.geojson (RFC 7946: a FeatureCollection, one LineString [lon, lat, h] per polyline,
/// properties stamp_s, side, confidence) and boundaries.kml (one Placemark per side, a MultiGeometry
/// of its LineStrings) in \p out_dir: each point p_map through T_enu_map, then WGS84 at the origin.
void writeGeoBoundaries(const std::string& out_dir, const std::vector<GeoPolyline>& lines, const Georef& g);

/// The geo-referenced trajectory files (trajectory_enu.tum, trajectory_geo.csv, .geojson, .kml) of
/// T_enu_lidar in the ENU frame \p enu.
void writeGeoTrajectory(const std::string& out_dir, const std::vector<double>& stamps_s,
                        const mapping::PoseVector& T_enu_lidar, const gnss::EnuFrame& enu);

}  // namespace roadslam::jobs

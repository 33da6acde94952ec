#include "roadslam/jobs/gnss_outputs.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <cstdio>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/pipeline/live_gnss.h"

namespace roadslam::jobs {
namespace {

const char* useName(gnss_fusion::FixUse u) {
  switch (u) {
    case gnss_fusion::FixUse::Used: return "used";
    case gnss_fusion::FixUse::Rejected: return "rejected";
    case gnss_fusion::FixUse::Unmatched: return "unmatched";
  }
  return "?";
}

nlohmann::json matrixJson(const Eigen::Isometry3d& T) {
  nlohmann::json rows = nlohmann::json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({T.matrix()(r, 0), T.matrix()(r, 1), T.matrix()(r, 2), T.matrix()(r, 3)});
  return rows;
}

}  // namespace

GnssInput readGnssInput(const std::string& path, const gnss_fusion::GnssFusionParams& p) {
  GnssInput in;
  in.path = path;
  in.log = gnss::readNmeaLog(path);
  if (in.log.fixes.empty()) {
    throw std::runtime_error("GNSS log '" + path + "' holds no valid fix (" + std::to_string(in.log.counters.lines) +
                             " lines, " + std::to_string(in.log.counters.bad_checksum) + " with a bad checksum, " +
                             std::to_string(in.log.counters.no_fix) + " epochs without a fix)");
  }
  in.origin = in.log.fixes.front().position;
  const gnss::EnuFrame enu(in.origin);
  for (const auto& f : in.log.fixes) {
    gnss_fusion::GnssFactor g;
    g.t_s = f.stamp(p.receiver_time);
    g.p_enu = enu.toEnu(f.position);
    g.cov = f.covarianceEnu(p.uere_m, p.fallback_sigma_m);
    in.factors.push_back(g);
  }
  return in;
}

std::string chooseGpsSource(const std::map<std::string, std::size_t>& sources, const std::string& wanted,
                            const std::string& input) {
  if (wanted.empty() && sources.size() <= 1) return sources.empty() ? "" : sources.begin()->first;
  if (!wanted.empty() && sources.count(wanted)) return wanted;
  std::string present;
  for (const auto& [label, n] : sources)
    present += (present.empty() ? "" : ", ") + label + (n ? " (" + std::to_string(n) + (n == 1 ? " record)" : " records)") : "");
  if (!wanted.empty()) {
    throw std::runtime_error("--gnss-label " + wanted + ": '" + input + "' has no GPS source of that label (" +
                             (present.empty() ? "it has none" : "it has " + present) + ")");
  }
  throw std::runtime_error("'" + input + "' carries several GPS sources (" + present +
                           "); choose the one to fuse with --gnss-label LABEL");
}

GnssInput gnssInputFromFixes(const std::vector<gnss::GnssFix>& fixes, const std::string& describe,
                             const gnss_fusion::GnssFusionParams& p) {
  GnssInput in;
  in.path = describe;
  for (const auto& f : fixes) {
    ++in.log.counters.epochs;
    if (!f.valid()) {
      ++in.log.counters.no_fix;
      continue;
    }
    in.log.fixes.push_back(f);
  }
  in.log.counters.fixes = in.log.fixes.size();
  if (in.log.fixes.empty()) throw std::runtime_error("the input carries no valid GPS fix (" + std::to_string(fixes.size()) + " fixes read)");
  in.origin = in.log.fixes.front().position;
  const gnss::EnuFrame enu(in.origin);
  for (const auto& f : in.log.fixes) in.factors.push_back(pipeline::recordedFixFactor(f, f.stamp(p.receiver_time), enu, p));
  return in;
}

namespace {
std::string tumLine(double t_s, const Eigen::Isometry3d& T) {
  char line[200];
  const Eigen::Vector3d t = T.translation();
  const Eigen::Quaterniond q(T.rotation());
  std::snprintf(line, sizeof(line), "%.6f %.4f %.4f %.4f %.9f %.9f %.9f %.9f\n", t_s, t.x(), t.y(), t.z(), q.x(),
                q.y(), q.z(), q.w());
  return line;
}
}  // namespace

nlohmann::json writeOnlineGnss(const std::string& dir, const std::vector<double>& st, const mapping::PoseVector& T_odom,
                               const GnssInput& in, const gnss_fusion::GnssFusionParams& p) {
  gnss_fusion::GnssOnlineStats s;
  const auto online = gnss_fusion::replayOnline(st, T_odom, in.factors, p, &s);
  std::string tum;
  std::size_t anchored = 0;
  for (std::size_t i = 0; i < online.size(); ++i) {
    if (!online[i]) continue;
    tum += tumLine(st[i], *online[i]);
    ++anchored;
  }
  if (anchored) writeFileAtomically(dir + "/trajectory_enu_online.tum", tum);
  return {{"frames", online.size()},   {"anchored_frames", anchored},
          {"solves", s.solves},        {"failed_solves", s.failed},
          {"ms_per_solve", s.solves ? s.ms_total / double(s.solves) : 0.0}, {"ms_max", s.ms_max}};
}

Georef readGeoref(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read georeference '" + path + "'");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": not JSON (" + e.what() + ")");
  }
  Georef g;
  try {
    const auto& o = j.at("enu_origin");
    g.origin = {o.at("lat_deg").get<double>(), o.at("lon_deg").get<double>(), o.at("h_m").get<double>()};
    const auto& M = j.at("T_enu_map");
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) g.T_enu_map.matrix()(r, c) = M.at(std::size_t(r)).at(std::size_t(c)).get<double>();
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": enu_origin {lat_deg, lon_deg, h_m} and T_enu_map (4x4) expected (" + e.what() + ")");
  }
  return g;
}

void writeGeoBoundaries(const std::string& dir, const std::vector<GeoPolyline>& lines, const Georef& g) {
  const gnss::EnuFrame enu(g.origin);
  nlohmann::json features = nlohmann::json::array();
  std::map<std::string, std::string> kml;  // side -> its LineStrings
  char buf[96];
  for (const auto& l : lines) {
    nlohmann::json coords = nlohmann::json::array();
    std::string& k = kml[l.side];
    k += "<LineString><altitudeMode>absolute</altitudeMode><coordinates>";
    for (const auto& p : l.p_map) {
      const gnss::Geodetic q = enu.toGeodetic(g.T_enu_map * p);
      coords.push_back({std::round(q.lon_deg * 1e9) / 1e9, std::round(q.lat_deg * 1e9) / 1e9, std::round(q.h_m * 1e3) / 1e3});
      std::snprintf(buf, sizeof(buf), "%.9f,%.9f,%.3f ", q.lon_deg, q.lat_deg, q.h_m);
      k += buf;
    }
    k += "</coordinates></LineString>\n";
    features.push_back({{"type", "Feature"},
                        {"properties", {{"stamp_s", l.stamp_s}, {"side", l.side}, {"confidence", l.confidence}}},
                        {"geometry", {{"type", "LineString"}, {"coordinates", coords}}}});
  }
  writeFileAtomically(dir + "/boundaries.geojson",
                      nlohmann::json{{"type", "FeatureCollection"}, {"features", features}}.dump() + "\n");
  std::string doc = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n"
                    "<Document><name>roadslam road boundaries</name>\n";
  for (const auto& [side, strings] : kml)
    doc += "<Placemark><name>" + side + " boundary</name><MultiGeometry>\n" + strings + "</MultiGeometry></Placemark>\n";
  writeFileAtomically(dir + "/boundaries.kml", doc + "</Document>\n</kml>\n");
}

void writeGeoTrajectory(const std::string& dir, const std::vector<double>& st, const mapping::PoseVector& T,
                        const gnss::EnuFrame& enu) {
  std::string tum, csv = "t,lat_deg,lon_deg,h_m,utm_zone,easting_m,northing_m\n", coords, kml;
  char line[320];
  int zone = -1;
  nlohmann::json line_coords = nlohmann::json::array();
  for (size_t i = 0; i < T.size(); ++i) {
    const Eigen::Vector3d t = T[i].translation();
    tum += tumLine(st[i], T[i]);
    const gnss::Geodetic g = enu.toGeodetic(t);
    const gnss::Utm u = gnss::utmFromGeodetic(g, zone);
    zone = u.zone;
    std::snprintf(line, sizeof(line), "%.6f,%.9f,%.9f,%.4f,%s,%.4f,%.4f\n", st[i], g.lat_deg, g.lon_deg, g.h_m,
                  u.zoneName().c_str(), u.easting_m, u.northing_m);
    csv += line;
    line_coords.push_back({std::round(g.lon_deg * 1e9) / 1e9, std::round(g.lat_deg * 1e9) / 1e9,
                           std::round(g.h_m * 1e3) / 1e3});
    std::snprintf(line, sizeof(line), "%.9f,%.9f,%.3f ", g.lon_deg, g.lat_deg, g.h_m);
    kml += line;
  }
  writeFileAtomically(dir + "/trajectory_enu.tum", tum);
  writeFileAtomically(dir + "/trajectory_geo.csv", csv);
  const nlohmann::json geo = {
      {"type", "FeatureCollection"},
      {"features",
       {{{"type", "Feature"},
         {"properties", {{"name", "roadslam trajectory"}, {"frames", T.size()}}},
         {"geometry", {{"type", "LineString"}, {"coordinates", line_coords}}}}}}};
  writeFileAtomically(dir + "/trajectory.geojson", geo.dump() + "\n");
  writeFileAtomically(dir + "/trajectory.kml",
                      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<kml xmlns=\"http://www.opengis.net/kml/2.2\">\n"
                      "<Document><name>roadslam trajectory</name>\n<Placemark><name>trajectory</name>\n"
                      "<LineString><altitudeMode>absolute</altitudeMode><coordinates>\n" +
                          kml + "\n</coordinates></LineString>\n</Placemark>\n</Document>\n</kml>\n");
}

nlohmann::json writeEnuMaps(const std::string& dir, const std::vector<mapping::Keyframe>& kfs,
                            const std::vector<double>& st, const mapping::PoseVector& T_enu, const mapping::MapOutputParams& p) {
  const std::string enu_dir = dir + "/enu";
  std::error_code ec;
  std::filesystem::create_directories(enu_dir, ec);
  if (ec) throw std::runtime_error("cannot create '" + enu_dir + "': " + ec.message());
  mapping::PoseVector T_enu_kf;
  for (const auto& kf : kfs) T_enu_kf.push_back(gnss_fusion::interpolatePose(st, T_enu, kf.stamp_s));
  const auto points = mapping::buildPointMap(kfs, T_enu_kf, p.point_map.voxel_m);
  mapping::writePly(enu_dir + "/map.ply", points);
  mapping::writePcd(enu_dir + "/map.pcd", points);
  const mapping::Grid2D grid = mapping::buildGrid(kfs, T_enu_kf, p.grid);
  mapping::writeGridPng(enu_dir + "/grid.png", enu_dir + "/grid.yaml", grid);
  std::size_t occ = 0, fre = 0;
  for (const auto c : grid.cells) {
    occ += c == 100;
    fre += c == 0;
  }
  return {{"dir", enu_dir}, {"points", points.size()}, {"grid_occupied_cells", occ}, {"grid_free_cells", fre}};
}

nlohmann::json fuseAndWriteGnss(const std::string& dir, const std::vector<double>& st, const mapping::PoseVector& T_map,
                                const GnssInput& in, const gnss_fusion::GnssFusionParams& p, mapping::PoseVector* T_enu_out) {
  nlohmann::json j;
  j["input"] = in.path;
  j["nmea"] = in.log.counters.named();
  j["problems"] = in.log.problems;
  j["origin"] = {{"lat_deg", in.origin.lat_deg}, {"lon_deg", in.origin.lon_deg}, {"h_m", in.origin.h_m}};
  const gnss_fusion::GnssFusionResult r = gnss_fusion::fuseGnss(st, T_map, in.factors, p);
  j["status"] = r.status;
  j["fixes"] = in.factors.size();
  j["fixes_used"] = r.used;
  j["fixes_rejected"] = r.rejected;
  j["fixes_unmatched"] = r.unmatched;
  j["iterations"] = r.iterations;
  j["converged"] = r.converged;
  j["rms_horizontal_residual_m"] = r.rms_inlier_m;
  j["ms"] = r.ms;
  if (!r.ok) return j;
  if (T_enu_out) *T_enu_out = r.T_enu_node;
  const gnss::EnuFrame enu(in.origin);
  writeGeoTrajectory(dir, st, r.T_enu_node, enu);
  std::string fixes = "t,e_m,n_m,u_m,sigma_e_m,sigma_n_m,use\n";
  char line[200];
  for (size_t k = 0; k < in.factors.size(); ++k) {
    const auto& f = in.factors[k];
    std::snprintf(line, sizeof(line), "%.6f,%.4f,%.4f,%.4f,%.3f,%.3f,%s\n", f.t_s, f.p_enu.x(), f.p_enu.y(), f.p_enu.z(),
                  std::sqrt(f.cov(0, 0)), std::sqrt(f.cov(1, 1)), useName(r.fix_use[k]));
    fixes += line;
  }
  writeFileAtomically(dir + "/gnss_fixes.csv", fixes);
  // the map's origin in UTM, with the rotation and scale from ENU to the UTM grid there
  const Eigen::Vector3d o = r.T_enu_map.translation();
  const gnss::Utm u = gnss::utmFromGeodetic(enu.toGeodetic(o));
  const double yaw_enu_map = std::atan2(r.T_enu_map.rotation()(1, 0), r.T_enu_map.rotation()(0, 0));
  const nlohmann::json georef = {
      {"enu_origin", j["origin"]},
      {"T_enu_map", matrixJson(r.T_enu_map)},
      {"utm_offset", {{"zone", u.zoneName()}, {"easting_m", u.easting_m}, {"northing_m", u.northing_m}, {"h_m", u.h_m},
                      {"meridian_convergence_deg", u.convergence_rad * 180 / M_PI}, {"scale", u.scale}}},
      {"map_yaw_from_east_deg", yaw_enu_map * 180 / M_PI},
      {"note", "map point p [m] -> ENU e = T_enu_map p -> UTM (E, N) = (easting, northing) + scale * "
               "Rot(meridian_convergence) (e_east, e_north) (counter-clockwise), h = h_m + e_up; exact per point: "
               "trajectory_geo.csv"}};
  writeFileAtomically(dir + "/map_georef.json", georef.dump(1) + "\n");
  j["T_enu_map"] = matrixJson(r.T_enu_map);
  j["utm_offset"] = georef["utm_offset"];
  return j;
}

}  // namespace roadslam::jobs

// GNSS at the end of roadslam-map, end to end on the small simulated loop: the simulator's receiver
// (10 Hz, 1 m noise, a 50 m multipath jump) fused into the job's odometry trajectory through
// runMapJob's --gnss path; the outputs read back and scored against the simulator's truth in its world
// frame, which is the ENU frame at ([scenario] origin, [gnss] origin_h_m) (GeographicLib converts).
#include <gtest/gtest.h>

#include <iostream>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <tuple>

#include "roadslam/datasets/trajectory_io.h"
#include "roadslam/gnss/geo.h"
#include "roadslam/gnss_fusion/gnss_fusion.h"
#include "roadslam/jobs/gnss_outputs.h"
#include "roadslam/jobs/map_job.h"
#include "roadslam/sources/recording.h"
#include "sim_cache.h"

using namespace roadslam;

TEST(GnssJob, SmallLoopFusedGeoreferencedOutputs) {
  auto sp = jobs::test::smallLoop();
  const std::string sim_dir = jobs::test::simulateOnce(sp);
  sp.gnss.enabled = true;
  sp.gnss.multipath_start_s = 20;
  sp.gnss.multipath_duration_s = 2;
  const sim::Simulator s(sp);
  // the run's inputs beside its output folder, never in it (runfolder/output_folder.h)
  const std::string out = std::string(ROADSLAM_BINARY_DIR) + "/test-out/map-job-small-loop-gnss";
  const std::string in = out + "-inputs";
  std::filesystem::remove_all(out);
  std::filesystem::create_directories(in);
  const auto gt = datasets::readTum(sim_dir + "/gt_trajectory.tum");
  const auto run = sim::writeGnss(s, gt.stamps_s.back() - static_cast<double>(sp.start_epoch_s), in + "/");
  // the antenna in the lidar frame: [gnss] lever arm (vehicle frame) less the lidar mount (no rotation)
  std::ifstream def(std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini");
  std::stringstream ini;
  ini << def.rdbuf();
  std::string text = ini.str();
  const auto at = text.find("[gnss_fusion]");
  ASSERT_NE(at, std::string::npos);
  text = text.substr(0, at) + "[gnss_fusion]\nlever_x_m = " + std::to_string(sp.gnss.lever_x_m - sp.lidar.mount_x_m) +
         "\nlever_y_m = " + std::to_string(sp.gnss.lever_y_m - sp.lidar.mount_y_m) + "\nlever_z_m = " +
         std::to_string(sp.gnss.lever_z_m - sp.lidar.mount_height_m) + "\n";
  std::ofstream(in + "/map-gnss.ini") << text;

  jobs::MapRequest req;
  req.config_path = in + "/map-gnss.ini";
  req.input_path = sim_dir + "/velodyne.pcap";
  req.gnss_path = in + "/gnss.nmea";
  req.out_dir = out;
  req.progress = false;
  req.allow_unknown_keys = true;  // the cut-down [gnss_fusion] leaves the other keys at their defaults
  req.maps = false;  // the odometry alone: the fusion takes any trajectory, and the test stays short
  const auto o = jobs::runMapJob(req);
  const auto& g = o.summary["gnss"];
  ASSERT_EQ(g["status"], "ok") << g.dump(1);
  EXPECT_EQ(g["fixes_rejected"].get<size_t>(), run.multipath_epochs) << g.dump(1);
  EXPECT_EQ(g["nmea"]["bad checksum"].get<int>(), 0);

  // the fused trajectory against the truth, in the simulator's world (ENU) frame
  const gnss::Geodetic origin{g["origin"]["lat_deg"], g["origin"]["lon_deg"], g["origin"]["h_m"]};
  const gnss::EnuFrame fused_enu(origin), world({sp.origin_lat_deg, sp.origin_lon_deg, sp.gnss.origin_h_m});
  const auto fused = datasets::readTum(out + "/trajectory_enu.tum");
  ASSERT_GT(fused.poses.size(), 300u);
  double sq = 0;
  for (size_t i = 0; i < fused.poses.size(); ++i) {
    const Eigen::Vector3d p = world.toEnu(fused_enu.toGeodetic(fused.poses[i].translation()));
    const Eigen::Vector3d t = gnss_fusion::interpolatePose(gt.stamps_s, gt.poses, fused.stamps_s[i]).translation();
    sq += (p - t).head<2>().squaredNorm();
  }
  EXPECT_LT(std::sqrt(sq / fused.poses.size()), 0.30);

  // the online mode (causal, on the odometry's own poses): same ENU frame, anchored within seconds,
  // worse than the batch (it cannot use later fixes), better than the fixes' 1 m noise
  const auto online = datasets::readTum(out + "/trajectory_enu_online.tum");
  EXPECT_GT(online.poses.size(), fused.poses.size() * 8 / 10) << g["online"].dump();  // 473 of 516 when written
  double sq_on = 0;
  for (size_t i = 0; i < online.poses.size(); ++i) {
    const Eigen::Vector3d p = world.toEnu(fused_enu.toGeodetic(online.poses[i].translation()));
    const Eigen::Vector3d t = gnss_fusion::interpolatePose(gt.stamps_s, gt.poses, online.stamps_s[i]).translation();
    sq_on += (p - t).head<2>().squaredNorm();
  }
  const double ate_online = std::sqrt(sq_on / std::max<size_t>(1, online.poses.size()));
  std::cout << "online 2D ATE " << ate_online << " m, batch " << std::sqrt(sq / fused.poses.size()) << " m\n";
  EXPECT_LT(ate_online, 0.8);
  EXPECT_EQ(g["online"]["anchored_frames"].get<size_t>(), online.poses.size());

  // road boundaries in GeoJSON / KML (roadslam-bounds --georef): a polyline through the map-frame
  // positions of two frames lands, through map_georef.json, where the fused trajectory put them
  // (within the fusion's own correction of the odometry), and its WGS84 goes back to ENU within 1 mm
  const auto odo = datasets::readTum(out + "/trajectory_odometry.tum");
  ASSERT_EQ(odo.poses.size(), fused.poses.size());
  const jobs::Georef gr = jobs::readGeoref(out + "/map_georef.json");
  jobs::GeoPolyline line;
  line.side = "left";
  for (size_t i : {size_t(0), fused.poses.size() / 2}) line.p_map.push_back(odo.poses[i].translation());
  jobs::writeGeoBoundaries(out, {line}, gr);
  nlohmann::json bj;
  std::ifstream(out + "/boundaries.geojson") >> bj;
  const auto& bc = bj["features"][0]["geometry"]["coordinates"];
  ASSERT_EQ(bc.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const size_t i = k == 0 ? 0 : fused.poses.size() / 2;
    const gnss::Geodetic q{bc[k][1].get<double>(), bc[k][0].get<double>(), bc[k][2].get<double>()};
    const Eigen::Vector3d e = fused_enu.toEnu(q);
    EXPECT_LT((e - gr.T_enu_map * line.p_map[k]).norm(), 0.002);
    EXPECT_LT((e - fused.poses[i].translation()).head<2>().norm(), 1.0);
  }
  std::ifstream bk(out + "/boundaries.kml");
  const std::string kb((std::istreambuf_iterator<char>(bk)), std::istreambuf_iterator<char>());
  EXPECT_NE(kb.find("<name>left boundary</name>"), std::string::npos);

  // GeoJSON and KML: one coordinate per frame, [lon, lat, h] the same point as trajectory_geo.csv
  nlohmann::json gj;
  std::ifstream(out + "/trajectory.geojson") >> gj;
  const auto& coords = gj["features"][0]["geometry"]["coordinates"];
  ASSERT_EQ(coords.size(), fused.poses.size());
  const gnss::Geodetic g0 = fused_enu.toGeodetic(fused.poses[0].translation());
  EXPECT_NEAR(coords[0][0].get<double>(), g0.lon_deg, 1e-8);
  EXPECT_NEAR(coords[0][1].get<double>(), g0.lat_deg, 1e-8);
  std::ifstream kml(out + "/trajectory.kml");
  std::string k((std::istreambuf_iterator<char>(kml)), std::istreambuf_iterator<char>());
  EXPECT_NE(k.find("<LineString>"), std::string::npos);
  // map_georef.json: a map point through its UTM offset formula lands within 1 cm of its exact UTM
  nlohmann::json geo;
  std::ifstream(out + "/map_georef.json") >> geo;
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) M(r, c) = geo["T_enu_map"][r][c];
  Eigen::Isometry3d T_enu_map(M);
  const auto& u = geo["utm_offset"];
  const double conv = u["meridian_convergence_deg"].get<double>() * M_PI / 180, k0 = u["scale"];
  for (const Eigen::Vector3d& p_map : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(80, -40, 2), Eigen::Vector3d(-30, 60, 0)}) {
    const Eigen::Vector3d e = T_enu_map * p_map - T_enu_map.translation();
    const double E = u["easting_m"].get<double>() + k0 * (std::cos(conv) * e.x() - std::sin(conv) * e.y());
    const double N = u["northing_m"].get<double>() + k0 * (std::sin(conv) * e.x() + std::cos(conv) * e.y());
    const gnss::Utm exact = gnss::utmFromGeodetic(fused_enu.toGeodetic(T_enu_map * p_map));
    EXPECT_NEAR(E, exact.easting_m, 0.01);
    EXPECT_NEAR(N, exact.northing_m, 0.01);
  }
}

// Maps rebuilt at the fused poses: keyframe points land at T_enu_lidar(stamp) p (the pose
// interpolated at the keyframe's stamp), read back from enu/map.ply.
TEST(GnssJob, EnuMapsAtTheFusedPoses) {
  const std::string out = std::string(ROADSLAM_BINARY_DIR) + "/test-out/gnss-enu-maps";
  std::filesystem::create_directories(out);
  std::vector<mapping::Keyframe> kfs(2);
  kfs[0].stamp_s = 10.0;
  kfs[1].stamp_s = 10.5;  // halfway between the two poses
  for (auto& kf : kfs)
    for (int i = 0; i < 5; ++i) kf.points_lidar.emplace_back(float(2 * i + 3), float(i % 2 ? 4 : -4), 0.5f);
  mapping::PoseVector T(2, Eigen::Isometry3d::Identity());
  T[0].translation() = Eigen::Vector3d(100, 200, 3);
  T[1].linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T[1].translation() = Eigen::Vector3d(110, 204, 3);
  const std::vector<double> st{10.0, 11.0};
  mapping::MapOutputParams mp;
  mp.point_map.voxel_m = 0.05;
  const auto j = jobs::writeEnuMaps(out, kfs, st, T, mp);
  EXPECT_EQ(j["points"].get<size_t>(), 10u);
  std::ifstream ply(out + "/enu/map.ply", std::ios::binary);
  std::string header, line;
  while (std::getline(ply, line) && line != "end_header") header += line + "\n";
  std::vector<Eigen::Vector3f> pts(10);
  ply.read(reinterpret_cast<char*>(pts.data()), std::streamsize(pts.size() * sizeof(Eigen::Vector3f)));
  ASSERT_TRUE(ply) << header;
  const Eigen::Isometry3d T_mid = gnss_fusion::interpolatePose(st, T, 10.5);
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_LT((pts[i].cast<double>() - T[0] * kfs[0].points_lidar[i].cast<double>()).norm(), 1e-4);
    EXPECT_LT((pts[5 + i].cast<double>() - T_mid * kfs[1].points_lidar[i].cast<double>()).norm(), 1e-4);
  }
  EXPECT_TRUE(std::filesystem::exists(out + "/enu/grid.png"));
  EXPECT_TRUE(std::filesystem::exists(out + "/enu/grid.yaml"));
}

// --gnss-from-input on a rawlog with two GPS sources: the bundled box-room capture converted to a
// rawlog (its Velodyne's 5 RMC position packets become CObservationGPS "GPS") followed by a second
// rawlog of 3 receiver epochs under "RECEIVER" (concatenated gzip members read as one stream).
// Several sources and no choice, or a label that is absent, is refused before the run naming both;
// a chosen source is fused alone (its fix count, not the 8 of the mix); a one-source rawlog needs
// no choice.
TEST(GnssJob, FromInputFusesOneChosenGpsSource) {
  const std::string dir = std::string(ROADSLAM_BINARY_DIR) + "/test-out/gnss-from-input-sources";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  sources::convertToRawlog(std::string(ROADSLAM_SOURCE_DIR) + "/rawlogs/boxroom-vlp16.pcap", dir + "/box.rawlog");
  std::ofstream(dir + "/r.nmea") << "$GPRMC,000001.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*5A\n"
                                    "$GPRMC,000002.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*59\n"
                                    "$GPRMC,000003.00,A,4808.0000,N,01134.0000,E,0.0,0.0,010124,,,A*58\n";
  ASSERT_EQ(rawlog::nmeaLogToRawlog(dir + "/r.nmea", dir + "/r.rawlog", "RECEIVER").epochs, 3u);
  {
    std::ofstream two(dir + "/two.rawlog", std::ios::binary);
    for (const char* part : {"/box.rawlog", "/r.rawlog"}) two << std::ifstream(dir + part, std::ios::binary).rdbuf();
  }
  auto run = [&](const std::string& input, const std::string& label) {
    jobs::MapRequest req;
    req.config_path = std::string(ROADSLAM_SOURCE_DIR) + "/ini/default.ini";
    req.input_path = dir + input;
    req.out_dir = dir + "/out" + input;  // a run folder per input
    req.progress = false;
    req.maps = false;
    req.gnss_from_input = true;
    req.gnss_label = label;
    return jobs::runMapJob(req);
  };
  auto message = [&](const std::string& label) {
    try {
      run("/two.rawlog", label);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("").find("several GPS sources (GPS (5 records), RECEIVER (3 records))"), std::string::npos) << message("");
  EXPECT_NE(message("CAN_GPS").find("--gnss-label CAN_GPS"), std::string::npos);
  EXPECT_NE(message("CAN_GPS").find("it has GPS (5 records), RECEIVER (3 records)"), std::string::npos) << message("CAN_GPS");
  for (const auto& [input, label, fixes] : {std::tuple<std::string, std::string, size_t>{"/two.rawlog", "RECEIVER", 3},
                                            {"/two.rawlog", "GPS", 5}, {"/box.rawlog", "", 5}}) {
    const auto o = run(input, label);
    const auto& g = o.summary["gnss"];
    EXPECT_EQ(g["fixes"].get<size_t>(), fixes) << input << " " << label << ": " << g.dump(1);
    EXPECT_NE(g["input"].get<std::string>().find("(" + (label.empty() ? std::string("GPS") : label) + ")"), std::string::npos);
  }
}

// The simulated GNSS receiver: its NMEA log, read back by libs/gnss's parser and put into the world
// (ENU) frame with GeographicLib, matches the truth it writes: white-noise statistics, the scripted
// outage (no fix, counted by the parser), the 50 m multipath jump, and the tunnel outage.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "roadslam/gnss/geo.h"
#include "roadslam/gnss/nmea.h"
#include "roadslam/sim/gnss_output.h"
#include "roadslam/sim/simulator.h"

using namespace roadslam::sim;

namespace {
struct Row {
  double t;
  Eigen::Vector3d truth, meas;
  std::string state;
};
std::vector<Row> readGt(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ss(line);
    Row r;
    double lat, lon, h;
    ss >> r.t >> r.truth.x() >> r.truth.y() >> r.truth.z() >> lat >> lon >> h >> r.meas.x() >> r.meas.y() >> r.meas.z() >> r.state;
    rows.push_back(r);
  }
  return rows;
}
std::string outDir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("roadslam_sim_gnss_" + name);
  std::filesystem::create_directories(d);
  return d.string() + "/";
}
}  // namespace

TEST(SimGnss, NmeaLogMatchesTruthWithOutageAndMultipath) {
  ScenarioParams p = ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/highway.ini");
  p.gnss.enabled = true;
  p.gnss.rate_hz = 10;
  p.gnss.outage_start_s = 10;
  p.gnss.outage_duration_s = 5;
  p.gnss.multipath_start_s = 20;
  p.gnss.multipath_duration_s = 2;
  const Simulator sim(p);
  const std::string d = outDir("highway");
  const GnssRun run = writeGnss(sim, 30.0, d);
  EXPECT_EQ(run.epochs, 301u);
  EXPECT_EQ(run.outage_epochs, 50u);
  EXPECT_EQ(run.multipath_epochs, 20u);
  const auto log = roadslam::gnss::readNmeaLog(d + "gnss.nmea");
  EXPECT_EQ(log.counters.bad_checksum, 0u);
  EXPECT_EQ(log.counters.no_fix, 50u);
  ASSERT_EQ(log.fixes.size(), 251u);
  const auto gt = readGt(d + "gt_gnss.csv");
  ASSERT_EQ(gt.size(), 301u);
  const roadslam::gnss::EnuFrame enu({p.origin_lat_deg, p.origin_lon_deg, p.gnss.origin_h_m});
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sq = Eigen::Vector3d::Zero();
  int n = 0;
  size_t k = 0;
  for (const Row& r : gt) {
    if (r.state == "outage") continue;
    const auto& f = log.fixes[k++];
    ASSERT_NEAR(f.t_receiver_s, r.t, 1e-3);
    EXPECT_NEAR(f.t_receive_s - f.t_receiver_s, p.gnss.latency_s, 1e-3);
    const Eigen::Vector3d e = enu.toEnu(f.position);
    EXPECT_LT((e - r.meas).norm(), 1e-3);  // the log holds what the truth file says was measured
    const Eigen::Vector3d err = e - r.truth;
    if (r.state == "multipath") {
      EXPECT_NEAR(err.x(), 50.0, 6.0);  // bearing 90 deg: east
      continue;
    }
    sum += err;
    sq += err.cwiseProduct(err);
    ++n;
  }
  const Eigen::Vector3d mean = sum / n, sd = (sq / n - mean.cwiseProduct(mean)).cwiseSqrt();
  EXPECT_LT(mean.head<2>().norm(), 0.25);
  EXPECT_NEAR(sd.x(), 1.0, 0.15);
  EXPECT_NEAR(sd.y(), 1.0, 0.15);
  EXPECT_NEAR(sd.z(), 1.5, 0.25);
}

TEST(SimGnss, TunnelIsAnOutage) {
  ScenarioParams p = ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/tunnel.ini");
  p.gnss.enabled = true;
  p.gnss.rate_hz = 1;
  const Simulator sim(p);
  const std::string d = outDir("tunnel");
  const GnssRun run = writeGnss(sim, sim.duration_s(), d);
  // 500 m of tunnel at up to 60 km/h: at least 30 s without a fix
  EXPECT_GE(run.outage_epochs, 30u);
  for (const Row& r : readGt(d + "gt_gnss.csv")) {
    if (r.state != "outage") continue;
    EXPECT_GT(r.truth.x(), 200.0);
    EXPECT_LT(r.truth.x(), 800.0);
  }
}

// VeloView's own regression expectations (Testing/vlp-16.test, Testing/monterey.test, copied to
// the shared data as *.expected.test): frame count, points per frame, listed point values in
// VeloView's frame (x right, y forward, z up) = (-y, x, z) of ours.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "oracle_util.h"
#include "roadslam/velodyne/position.h"

using namespace roadslam;
using namespace roadslam::velodyne;
using roadslam::velodyne::test::dataFile;

namespace {

struct ExpectedPoint { int index; double x, y, z, intensity; };
struct Expected {
  int frame_count = -1;
  std::map<int, int> point_count;
  std::map<int, std::vector<ExpectedPoint>> points;
};

/// Reader for VeloView's TestReader format ("frame_count N", "frame K", "point_count M",
/// "point_values idx x y z intensity isDual").
Expected readExpected(const std::string& path) {
  Expected e;
  std::ifstream in(path);
  std::string key;
  int frame = -1;
  while (in >> key) {
    if (key == "frame_count") in >> e.frame_count;
    else if (key == "frame") in >> frame;
    else if (key == "point_count") in >> e.point_count[frame];
    else if (key == "point_values") {
      ExpectedPoint p;
      int dual = 0;
      in >> p.index >> p.x >> p.y >> p.z >> p.intensity >> dual;
      e.points[frame].push_back(p);
    }
  }
  return e;
}

void checkAgainstVeloView(const std::string& pcap, const std::string& calib,
                          const std::string& expected, Model model) {
  for (const auto& f : {pcap, calib, expected})
    if (!test::exists(f)) GTEST_SKIP() << "missing " << f;
  const Expected e = readExpected(expected);
  DecoderParams params;
  params.model = model;  // the VLP-16 capture reports the HDL-32E product byte
  params.calibration_file = calib;
  SweepStats stats;
  const std::vector<Scan> sweeps = test::sweepsOf(pcap, params, &stats);
  EXPECT_EQ(static_cast<int>(sweeps.size()), e.frame_count);
  EXPECT_EQ(stats.malformed(), 0u);
  ASSERT_GT(e.frame_count, 2);
  if (static_cast<int>(sweeps.size()) != e.frame_count) return;
  EXPECT_TRUE(sweeps.front().partial);
  EXPECT_TRUE(sweeps.back().partial);
  for (int i = 1; i + 1 < e.frame_count; ++i) EXPECT_FALSE(sweeps[i].partial) << i;
  for (const auto& [frame, count] : e.point_count)
    EXPECT_EQ(static_cast<int>(sweeps[frame].points.size()), count) << "frame " << frame;
  for (const auto& [frame, pts] : e.points) {
    for (const auto& ep : pts) {
      ASSERT_LT(ep.index, static_cast<int>(sweeps[frame].points.size()));
      const ScanPoint& p = sweeps[frame].points[ep.index];
      EXPECT_NEAR(-p.y, ep.x, 0.01) << "frame " << frame << " point " << ep.index;
      EXPECT_NEAR(p.x, ep.y, 0.01) << "frame " << frame << " point " << ep.index;
      EXPECT_NEAR(p.z, ep.z, 0.01) << "frame " << frame << " point " << ep.index;
      EXPECT_EQ(p.intensity, ep.intensity) << "frame " << frame << " point " << ep.index;
    }
  }
}

}  // namespace

TEST(OracleVeloView, Vlp16FramesPointCountsAndPoints) {
  checkAgainstVeloView(dataFile("veloview_vlp-16-test-90deg-1-50-frames.pcap"),
                       dataFile("veloview_calib_VLP-16.xml"),
                       dataFile("veloview_vlp-16.expected.test"), Model::VLP16);
}

TEST(OracleVeloView, Hdl32MontereyFramesPointCountsAndPoints) {
  checkAgainstVeloView(dataFile("veloview_monterey-first-100-packets.pcap"),
                       dataFile("veloview_calib_HDL-32.xml"),
                       dataFile("veloview_monterey.expected.test"), Model::HDL32);
}

TEST(OracleVeloView, MontereyHas299PositionPackets) {
  const std::string pcap = dataFile("veloview_monterey-first-100-packets.pcap");
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  // VeloView TestPositionReader expects 299 position packets; MANIFEST: $GPRMC 2012-12-11,
  // 37deg07.83'N 121deg39.29'W, 0.0 kn.
  const auto pos = pcap::readUdpDatagrams(pcap, kDefaultPositionPort);
  EXPECT_EQ(pos.size(), 299u);
  int fixes = 0;
  for (const auto& d : pos) {
    PositionPacket pp;
    ASSERT_TRUE(decodePositionPacket(d.payload.data(), d.payload.size(), pp));
    if (!pp.fix) continue;
    ++fixes;
    // 2012-12-11 (date -u -d 2012-12-11 +%s = 1355184000)
    EXPECT_EQ(std::floor(pp.fix->t_receiver_s / 86400) * 86400, 1355184000.0) << pp.nmea;
    EXPECT_NEAR(pp.fix->position.lat_deg, 37 + 7.83 / 60, 0.01 / 60);
    EXPECT_NEAR(pp.fix->position.lon_deg, -(121 + 39.29 / 60), 0.01 / 60);
    EXPECT_NEAR(pp.fix->speed_mps, 0.0, 0.1);
  }
  EXPECT_GT(fixes, 0);
  std::cout << "monterey: " << fixes << " RMC fixes in " << pos.size() << " position packets\n";
}

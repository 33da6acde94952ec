// MRPT's own expectations on its sample VLP-16 capture (CVelodyneScanner_unittest: 4 scans, GPS
// present; MANIFEST: $GPRMC 36deg49.748'N 002deg24.454'W), and MRPT's generatePointCloud on the
// same packets, which decodes only the first firing of each block: we must give about twice its points.
#include <gtest/gtest.h>

#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cstring>
#include <iostream>

#include "oracle_util.h"
#include "roadslam/velodyne/position.h"

using namespace roadslam;
using namespace roadslam::velodyne;
using roadslam::velodyne::test::dataFile;

namespace {
const std::string kPcap = "mrpt_sample_velodyne_vlp16_gps.pcap";
}

// MRPT's CVelodyneScanner test expects 4 scans from this file: it emits the partial first
// revolution (packets start at azimuth 118.88 deg) and loses the one in progress at end of file.
// 293 packets at 754/s = 0.389 s = 3.9 revolutions at 10 Hz: our assembler gives 5 sweeps,
// partial + 3 complete + partial; MRPT's 4 are our first 4.
TEST(OracleMrpt, Vlp16SampleSweepsMatchMrptScanCount) {
  const std::string pcap = dataFile(kPcap);
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  SweepStats stats;
  const auto sweeps = test::sweepsOf(pcap, DecoderParams{}, &stats);
  int complete = 0;
  for (const auto& s : sweeps) complete += s.partial ? 0 : 1;
  ASSERT_EQ(sweeps.size(), 5u);
  EXPECT_EQ(sweeps.size() - 1, 4u);  // MRPT's count: all but the sweep open at end of file
  EXPECT_EQ(complete, 3);
  EXPECT_TRUE(sweeps.front().partial);
  EXPECT_TRUE(sweeps.back().partial);
  EXPECT_EQ(stats.packets, 293u);
  EXPECT_EQ(stats.malformed(), 0u);
  for (const auto& s : sweeps) {
    if (s.partial) continue;
    // A 10 Hz VLP-16 revolution lasts about 0.1 s: the last firing of a full sweep near it.
    float t_max = 0;
    for (const auto& p : s.points) t_max = std::max(t_max, p.t);
    EXPECT_NEAR(t_max, 0.1, 0.01);
    EXPECT_GT(s.points.size(), 15000u);  // 75 packets x 384 channels, minus no-returns
    EXPECT_NEAR(s.stamp_s - sweeps[1].stamp_s, 0.1 * (&s - &sweeps[1]), 0.005);
  }
}

TEST(OracleMrpt, Vlp16SampleGpsFixesFromGprmc) {
  const std::string pcap = dataFile(kPcap);
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  const auto pos = pcap::readUdpDatagrams(pcap, kDefaultPositionPort);
  EXPECT_EQ(pos.size(), 57u);
  int fixes = 0;
  for (const auto& d : pos) {
    PositionPacket pp;
    ASSERT_TRUE(decodePositionPacket(d.payload.data(), d.payload.size(), pp));
    if (!pp.has_fix) continue;
    ++fixes;
    EXPECT_TRUE(pp.fix.valid);
    // Sentence: 3649.7478558,N,00224.4542928,W (MANIFEST rounds to 49.748' / 24.454').
    EXPECT_NEAR(pp.fix.latitude_deg, 36 + 49.7478558 / 60, 1e-9);
    EXPECT_NEAR(pp.fix.longitude_deg, -(2 + 24.4542928 / 60), 1e-9);
    EXPECT_NEAR(pp.fix.time_of_day_s, 8 * 3600 + 18 * 60 + 2, 1.0);
    EXPECT_NEAR(pp.fix.course_rad, 212.5 * M_PI / 180, 1e-9);
    EXPECT_EQ(pp.fix.year, 2016);
    EXPECT_EQ(pp.fix.month, 1);
    EXPECT_EQ(pp.fix.day, 21);
    EXPECT_NEAR(pp.fix.speed_mps, 0.03 * 1852 / 3600, 0.02);
  }
  EXPECT_GT(fixes, 0);
}

TEST(OracleMrpt, TwiceTheGeneratePointCloudPoints) {
  const std::string pcap = dataFile(kPcap);
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  const auto packets = pcap::readUdpDatagrams(pcap, kDefaultDataPort);
  DecoderParams params;
  params.min_range_m = 1.0;  // MRPT's TGeneratePointCloudParameters::minDistance default
  const Decoder decoder(params);
  constexpr std::size_t kChunk = 75;  // about one revolution at 10 Hz
  std::size_t ours_total = 0, mrpt_total = 0;
  for (std::size_t start = 0; start + kChunk <= packets.size(); start += kChunk) {
    mrpt::obs::CObservationVelodyneScan obs;
    obs.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("VLP16");
    std::vector<ScanPoint> ours;
    for (std::size_t i = start; i < start + kChunk; ++i) {
      const auto& p = packets[i].payload;
      ASSERT_EQ(decoder.decode(p.data(), p.size(), ours), DecodeStatus::Ok);
      mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket raw;
      static_assert(sizeof(raw) == kDataPacketSize);
      std::memcpy(&raw, p.data(), sizeof(raw));
      obs.scan_packets.push_back(raw);
    }
    obs.generatePointCloud();
    const std::size_t theirs = obs.point_cloud.x.size();
    ASSERT_GT(theirs, 0u);
    const double ratio = static_cast<double>(ours.size()) / static_cast<double>(theirs);
    std::cout << "packets " << start << "-" << start + kChunk << ": ours " << ours.size()
              << " MRPT " << theirs << " ratio " << ratio << "\n";
    EXPECT_GE(ratio, 1.9);
    EXPECT_LE(ratio, 2.1);
    ours_total += ours.size();
    mrpt_total += theirs;
  }
  std::cout << "total: ours " << ours_total << " MRPT " << mrpt_total << " ratio "
            << static_cast<double>(ours_total) / static_cast<double>(mrpt_total) << "\n";
}

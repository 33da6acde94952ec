// MRPT's own expectations on its sample VLP-16 capture (CVelodyneScanner_unittest: 4 scans, GPS
// present; MANIFEST: $GPRMC 36deg49.748'N 002deg24.454'W), and MRPT's generatePointCloud on the
// same packets, which decodes only the first firing of each block: we must give about twice its points.
#include <gtest/gtest.h>

#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cmath>
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
    if (!pp.fix) continue;
    ++fixes;
    EXPECT_TRUE(pp.fix->valid());
    // Sentence: 3649.7478558,N,00224.4542928,W (MANIFEST rounds to 49.748' / 24.454').
    EXPECT_NEAR(pp.fix->position.lat_deg, 36 + 49.7478558 / 60, 1e-9);
    EXPECT_NEAR(pp.fix->position.lon_deg, -(2 + 24.4542928 / 60), 1e-9);
    EXPECT_NEAR(pp.fix->time_of_day_s, 8 * 3600 + 18 * 60 + 2, 1.0);
    EXPECT_NEAR(pp.fix->course_rad, 212.5 * M_PI / 180, 1e-9);
    // 2016-01-21 (date -u -d 2016-01-21 +%s = 1453334400)
    EXPECT_EQ(std::floor(pp.fix->t_receiver_s / 86400) * 86400, 1453334400.0);
    EXPECT_NEAR(pp.fix->speed_mps, 0.03 * 1852 / 3600, 0.02);
  }
  EXPECT_GT(fixes, 0);
}

namespace {

/// Points of our decoder and of MRPT's generatePointCloud on chunks of \p chunk packets; checks
/// every chunk's ratio is within [lo, hi].
void comparePointCounts(const std::string& pcap, const std::string& mrpt_model, std::size_t kChunk,
                        double lo, double hi) {
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  const auto packets = pcap::readUdpDatagrams(pcap, kDefaultDataPort);
  // The comparison's precondition: at least one whole chunk, else the loop below compares nothing.
  ASSERT_GE(packets.size(), kChunk) << pcap << ": " << packets.size() << " data packets, fewer than one chunk of "
                                    << kChunk << ": nothing would be compared";
  DecoderParams params;
  params.min_range_m = 1.0;  // MRPT's TGeneratePointCloudParameters::minDistance default
  const Decoder decoder(params);
  std::size_t ours_total = 0, mrpt_total = 0;
  for (std::size_t start = 0; start + kChunk <= packets.size(); start += kChunk) {
    mrpt::obs::CObservationVelodyneScan obs;
    obs.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration(mrpt_model);
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
    EXPECT_GE(ratio, lo);
    EXPECT_LE(ratio, hi);
    ours_total += ours.size();
    mrpt_total += theirs;
  }
  ASSERT_GT(mrpt_total, 0u) << pcap << ": no chunk compared";
  std::cout << mrpt_model << " total: ours " << ours_total << " MRPT " << mrpt_total << " ratio "
            << static_cast<double>(ours_total) / static_cast<double>(mrpt_total) << "\n";
}

}  // namespace

TEST(OracleMrpt, Vlp16TwiceTheGeneratePointCloudPoints) {
  // MRPT decodes only the first of the two firings of each VLP-16 block.
  comparePointCounts(dataFile(kPcap), "VLP16", 75, 1.9, 2.1);  // 75 packets ~ one turn at 10 Hz
}

// MRPT 2.5.8 generatePointCloud emits laser ids 0..15 only, on the HDL-32E as well: it drops the
// upper 16 channels of every block. Our points from channels 0..15 must match its count.
TEST(OracleMrpt, Hdl32LowerSixteenLasersMatchGeneratePointCloud) {
  const std::string pcap = dataFile("mrpt_sample_velodyne_hdl32.pcap");
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  const auto packets = pcap::readUdpDatagrams(pcap, kDefaultDataPort);
  ASSERT_GE(packets.size(), 180u);
  mrpt::obs::CObservationVelodyneScan obs;
  obs.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("HDL32");
  DecoderParams params;
  params.min_range_m = 1.0;  // MRPT's minDistance default
  const Decoder decoder(params);
  std::vector<ScanPoint> ours;
  for (std::size_t i = 0; i < 180; ++i) {
    const auto& p = packets[i].payload;
    ASSERT_EQ(decoder.decode(p.data(), p.size(), ours), DecodeStatus::Ok);
    mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket raw;
    std::memcpy(&raw, p.data(), sizeof(raw));
    obs.scan_packets.push_back(raw);
  }
  obs.generatePointCloud();
  for (auto id : obs.point_cloud.laser_id) ASSERT_LT(id, 16);
  const Calibration& cal = decoder.calibration(Model::HDL32);
  std::size_t lower = 0;
  for (const auto& p : ours)
    for (int l = 0; l < 16; ++l) lower += cal.lasers[l].ring == p.ring ? 1 : 0;
  const double theirs = static_cast<double>(obs.point_cloud.x.size());
  std::cout << "HDL32 180 packets: ours " << ours.size() << " (lasers 0-15: " << lower << ") MRPT "
            << theirs << " ratio " << ours.size() / theirs << "\n";
  EXPECT_EQ(static_cast<double>(lower), theirs);  // same returns, same 1 m filter
  EXPECT_GE(ours.size() / theirs, 1.9);
}

// MRPT's sample_hdl32_dataset test expects 3 scans; as for the VLP-16 file, its count includes
// the partial first turn and misses the one open at end of file.
TEST(OracleMrpt, Hdl32SampleSweepsMatchMrptScanCount) {
  const std::string pcap = dataFile("mrpt_sample_velodyne_hdl32.pcap");
  if (!test::exists(pcap)) GTEST_SKIP() << "missing " << pcap;
  SweepStats stats;
  const auto sweeps = test::sweepsOf(pcap, DecoderParams{}, &stats);
  ASSERT_EQ(sweeps.size(), 4u);
  EXPECT_EQ(sweeps.size() - 1, 3u);
  EXPECT_FALSE(sweeps[1].partial);
  EXPECT_FALSE(sweeps[2].partial);
  EXPECT_EQ(stats.packets, 500u);
  EXPECT_EQ(stats.malformed(), 0u);
  EXPECT_EQ(stats.partial_sweeps, 2u);
}

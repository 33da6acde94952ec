// PcapPacketSource on the real MRPT VLP-16 capture (counts from its MANIFEST) and the lossless
// pcap -> rawlog -> packets round trip.
#include <gtest/gtest.h>

#include <filesystem>

#include "roadslam/pcap/pcap_writer.h"
#include "roadslam/sources/gps_fix.h"
#include "roadslam/sources/pcap_source.h"
#include "roadslam/sources/rawlog_source.h"
#include "roadslam/rawlog/rawlog_writer.h"
#include "test_packets.h"

using namespace roadslam::sources;
using namespace roadslam::rawlog;
namespace fs = std::filesystem;

namespace {
const std::string kMrptPcap =
    std::string(ROADSLAM_SHARED_DATA) + "/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap";

fs::path tempDir() {
  const fs::path d = fs::temp_directory_path() / ("roadslam_sources_pcap_" + std::to_string(getpid()));
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(PcapPacketSource, MrptSampleCountsMatchManifest) {
  if (!fs::exists(kMrptPcap)) GTEST_SKIP() << "missing " << kMrptPcap;
  PcapPacketSource src(kMrptPcap);
  std::size_t n = 0, fixes = 0;
  double last = 0;
  while (auto p = src.next()) {
    EXPECT_GE(p->stamp_s, last) << "packet " << n;
    last = p->stamp_s;
    if (p->dst_port == 8308) {
      auto fix = decodeGpsFix(*p);
      if (fix) {
        ++fixes;
        // MANIFEST: $GPRMC 36deg49.748'N 002deg24.454'W, 0.03 kn.
        EXPECT_NEAR(fix->position.lat_deg, test_support::kAlmeriaLat_deg, 1e-3);
        EXPECT_NEAR(fix->position.lon_deg, test_support::kAlmeriaLon_deg, 1e-3);
        EXPECT_LT(fix->speed_mps, 0.1);
      }
    }
    ++n;
  }
  EXPECT_TRUE(src.finished());
  EXPECT_EQ(src.stats().data_packets, 293u);      // MANIFEST: 293 data packets
  EXPECT_EQ(src.stats().position_packets, 57u);   // MANIFEST: 57 position packets
  EXPECT_EQ(src.stats().malformed_packets, 0u);
  EXPECT_EQ(fixes, 57u);
  EXPECT_EQ(n, 350u);
  EXPECT_NEAR(src.stats().last_stamp_s - src.stats().first_stamp_s, 0.39, 0.01);  // MANIFEST 0.39 s
}

TEST(PcapPacketSource, PcapToRawlogToPacketsIsByteIdentical) {
  if (!fs::exists(kMrptPcap)) GTEST_SKIP() << "missing " << kMrptPcap;
  std::vector<roadslam::velodyne::RawPacket> data;
  {
    PcapPacketSource src(kMrptPcap);
    while (auto p = src.next())
      if (p->dst_port == 2368) data.push_back(std::move(*p));
  }
  const fs::path path = tempDir() / "mrpt_sample.rawlog";
  {
    RawlogWriter w(path.string(), RawlogWriter::Params{});
    // Any grouping is lossless; 75 packets ~ one VLP-16 turn at 10 Hz.
    for (std::size_t i = 0; i < data.size(); i += 75)
      w.writeSweep({data.begin() + i, data.begin() + std::min(data.size(), i + 75)});
    w.close();
  }
  RawlogPacketSource back(path.string());
  std::size_t k = 0;
  while (auto p = back.next()) {
    ASSERT_LT(k, data.size());
    EXPECT_EQ(p->payload, data[k].payload) << "packet " << k;
    // Stamps of later packets come from the sensor clock: within the capture jitter.
    EXPECT_NEAR(p->stamp_s, data[k].stamp_s, 2e-3) << "packet " << k;
    ++k;
  }
  EXPECT_EQ(k, data.size());
  EXPECT_EQ(back.stats().missing_packets, PcapPacketSource(kMrptPcap).stats().missing_packets);
  fs::remove(path);
}

TEST(PcapPacketSource, NonVelodyneTrafficIsSkippedAndCounted) {
  const fs::path path = tempDir() / "dns.pcap";
  {
    roadslam::pcap::PcapWriter w(path.string());
    const std::vector<uint8_t> payload(60, 7);
    for (int i = 0; i < 12; ++i) w.writeUdp(1000.0 + i, 5353, 53, payload.data(), payload.size());
    const std::vector<uint8_t> wrong(1000, 1);  // right port, wrong size
    w.writeUdp(1013.0, 2368, 2368, wrong.data(), wrong.size());
    w.close();
  }
  PcapPacketSource src(path.string());
  EXPECT_FALSE(src.next().has_value());
  EXPECT_TRUE(src.finished());
  EXPECT_EQ(src.stats().skipped_packets, 12u);
  EXPECT_EQ(src.stats().malformed_packets, 1u);
  EXPECT_EQ(src.stats().packets, 0u);
  fs::remove(path);
}

// Round trip PcapWriter -> PcapReader, and frames of the other link types built byte by byte.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "pcap_test_util.h"
#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/pcap/pcap_writer.h"

using namespace roadslam::pcap;
using roadslam::pcap::test::tempPath;

TEST(PcapRoundTrip, StampsPortsAddressesAndPayloadSurvive) {
  const std::string path = tempPath("roundtrip.pcap");
  std::mt19937 rng(42);
  std::vector<std::vector<uint8_t>> payloads;
  std::vector<double> stamps;
  {
    PcapWriter w(path);
    for (int i = 0; i < 50; ++i) {
      std::vector<uint8_t> p(i % 2 ? 1206 : 512);
      for (auto& b : p) b = static_cast<uint8_t>(rng());
      const double stamp = 1453364282.0 + i * 0.001327 + 1e-7;
      w.writeUdp(stamp, 2368, i % 2 ? 2368 : 8308, p.data(), p.size(), 0xC0A801C9u + i, 0x0A000001u);
      payloads.push_back(p);
      stamps.push_back(stamp);
    }
    EXPECT_EQ(w.packetsWritten(), 50u);
    w.close();
    const uint8_t x = 0;
    EXPECT_THROW(w.writeUdp(0, 1, 2, &x, 1), std::runtime_error);
  }
  PcapReader r(path);
  EXPECT_EQ(r.linkType(), 1);
  UdpDatagram d;
  for (int i = 0; i < 50; ++i) {
    ASSERT_EQ(r.next(d), ReadStatus::Ok) << i;
    EXPECT_NEAR(d.stamp_s, stamps[i], 1.5e-6);  // microsecond stamps in the file
    EXPECT_EQ(d.stamp_ns % 1000, 0);
    EXPECT_NEAR(static_cast<double>(d.stamp_ns) * 1e-9, stamps[i], 1.5e-6);
    EXPECT_EQ(d.dst_port, i % 2 ? 2368 : 8308);
    EXPECT_EQ(d.src_port, 2368);
    EXPECT_EQ(d.src_ip, 0xC0A801C9u + i);
    EXPECT_EQ(d.dst_ip, 0x0A000001u);
    EXPECT_EQ(d.payload, payloads[i]);
  }
  EXPECT_EQ(r.next(d), ReadStatus::EndOfFile);
  EXPECT_TRUE(r.errorMessage().empty());
  EXPECT_EQ(r.stats().datagrams, 50u);
  EXPECT_EQ(r.stats().records, 50u);
  std::remove(path.c_str());
}

TEST(PcapRoundTrip, Ipv4HeaderChecksumIsValid) {
  const std::string path = tempPath("checksum.pcap");
  {
    PcapWriter w(path);
    const std::vector<uint8_t> p(1206, 0xAB);
    w.writeUdp(10.5, 2368, 2368, p.data(), p.size());
  }
  const std::vector<uint8_t> bytes = test::readFile(path);
  ASSERT_EQ(bytes.size(), 24u + 16u + 14u + 20u + 8u + 1206u);
  // Independent check (RFC 1071): summing the header including its checksum gives 0xFFFF.
  const uint8_t* ip = bytes.data() + 24 + 16 + 14;
  uint32_t sum = 0;
  for (int i = 0; i < 20; i += 2) sum += (ip[i] << 8) | ip[i + 1];
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  EXPECT_EQ(sum, 0xFFFFu);
  EXPECT_EQ((ip[2] << 8) | ip[3], 20 + 8 + 1206);  // IPv4 total length
  std::remove(path.c_str());
}

TEST(PcapLinkTypes, VlanSllSll2RawAndNullFramesAreDecoded) {
  const std::vector<uint8_t> udp_ip = test::ipv4Udp({1, 2, 3}, 7000, 2368);
  struct Case { int linktype; std::vector<uint8_t> prefix; };
  const std::vector<Case> cases = {
      {1, test::ethernet(0x8100, /*vlan_tags=*/2)},
      {113, test::sll(0x0800)},
      {276, test::sll2(0x0800)},
      {101, {}},  // LINKTYPE_RAW
      {228, {}},  // LINKTYPE_IPV4
      {0, {2, 0, 0, 0}},  // LINKTYPE_NULL, AF_INET little-endian
  };
  for (const auto& c : cases) {
    std::vector<uint8_t> frame = c.prefix;
    frame.insert(frame.end(), udp_ip.begin(), udp_ip.end());
    const std::string path = tempPath("link.pcap");
    test::writeClassicPcap(path, c.linktype, {frame, frame});
    std::string err;
    PcapReadStats st;
    const auto ds = readUdpDatagrams(path, 0, &err, &st);
    ASSERT_EQ(ds.size(), 2u) << "linktype " << c.linktype;
    EXPECT_EQ(ds[0].payload, (std::vector<uint8_t>{1, 2, 3}));
    EXPECT_EQ(ds[0].src_port, 7000);
    EXPECT_EQ(ds[0].dst_port, 2368);
    EXPECT_EQ(ds[1].stamp_s, 101.000002);  // second record stamp from writeClassicPcap
    EXPECT_EQ(ds[1].stamp_ns, 101000002000LL);
    EXPECT_TRUE(err.empty()) << err;
    std::remove(path.c_str());
  }
}

TEST(PcapLinkTypes, NanosecondCapturesKeepNanoseconds) {
  // Classic pcap with the nanosecond magic 0xA1B23C4D (pcap-savefile(5)).
  const std::string path = tempPath("nano.pcap");
  test::writeClassicPcap(path, 101, {test::ipv4Udp({7}, 1, 2)});
  std::vector<uint8_t> b = test::readFile(path);
  b[0] = 0x4D; b[1] = 0x3C; b[2] = 0xB2; b[3] = 0xA1;
  b[24 + 4] = 0x15; b[24 + 5] = 0xCD; b[24 + 6] = 0x5B; b[24 + 7] = 0x07;  // 123456789 ns
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(b.data()), b.size());
  const auto ds = readUdpDatagrams(path);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].stamp_ns, 100123456789LL);
  EXPECT_NEAR(ds[0].stamp_s, 100.123456789, 1e-9);
  std::remove(path.c_str());
}

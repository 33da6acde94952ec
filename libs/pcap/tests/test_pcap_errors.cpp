// Damaged, empty, missing and foreign captures: a clear message naming the file, no crash, and every
// good record before the damage.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "pcap_test_util.h"
#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/pcap/pcap_writer.h"

using namespace roadslam::pcap;
using roadslam::pcap::test::tempPath;

namespace {

std::string writeSample(const std::string& name, int n) {
  const std::string path = tempPath(name);
  PcapWriter w(path);
  std::vector<uint8_t> p(1206);
  for (int i = 0; i < n; ++i) {
    p[0] = static_cast<uint8_t>(i);
    w.writeUdp(1000.0 + i, 2368, 2368, p.data(), p.size());
  }
  return path;
}

}  // namespace

TEST(PcapErrors, MissingFileThrowsNamingTheFile) {
  const std::string path = "/nonexistent/dir/missing.pcap";
  try {
    PcapReader r(path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_THROW(PcapWriter w("/nonexistent/dir/out.pcap"), std::runtime_error);
}

TEST(PcapErrors, EmptyAndNonCaptureFilesThrowNamingTheFile) {
  for (const std::string& content : {std::string(), std::string("hello, this is not a pcap file")}) {
    const std::string path = tempPath("bad.pcap");
    std::ofstream(path) << content;
    try {
      PcapReader r(path);
      FAIL() << "no exception for content '" << content << "'";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    std::remove(path.c_str());
  }
}

TEST(PcapErrors, TruncatedFileKeepsGoodRecordsAndReportsIndex) {
  const std::string path = writeSample("trunc.pcap", 10);
  std::vector<uint8_t> bytes = test::readFile(path);
  const std::size_t record = 16 + 14 + 20 + 8 + 1206;
  bytes.resize(24 + 7 * record + 500);  // cut in the middle of record 7
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  PcapReader r(path);
  UdpDatagram d;
  int n = 0;
  while (r.next(d) == ReadStatus::Ok) {
    EXPECT_EQ(d.payload[0], n);
    ++n;
  }
  EXPECT_EQ(n, 7);
  EXPECT_EQ(r.status(), ReadStatus::Error);
  EXPECT_NE(r.errorMessage().find(path), std::string::npos) << r.errorMessage();
  EXPECT_NE(r.errorMessage().find("record 7"), std::string::npos) << r.errorMessage();
  EXPECT_EQ(r.next(d), ReadStatus::Error);  // sticky
  std::remove(path.c_str());
}

TEST(PcapErrors, OtherTrafficIsCountedNotReturned) {
  const std::vector<uint8_t> udp = test::ipv4Udp({9, 9}, 5, 2368);
  std::vector<std::vector<uint8_t>> frames;
  auto eth = [](uint16_t type, const std::vector<uint8_t>& body) {
    std::vector<uint8_t> f = test::ethernet(type);
    f.insert(f.end(), body.begin(), body.end());
    return f;
  };
  frames.push_back(eth(0x0806, std::vector<uint8_t>(28, 0)));       // ARP
  frames.push_back(eth(0x86DD, std::vector<uint8_t>(60, 0)));       // IPv6
  frames.push_back(eth(0x0800, test::ipv4Udp({1}, 1, 2, 6)));       // TCP
  frames.push_back(eth(0x0800, test::ipv4Udp({1}, 1, 2, 17, 0x2000)));  // first fragment
  frames.push_back(eth(0x0800, std::vector<uint8_t>(udp.begin(), udp.begin() + 10)));  // cut IP
  frames.push_back(eth(0x0800, udp));
  const std::string path = tempPath("other.pcap");
  test::writeClassicPcap(path, 1, frames);
  std::string err;
  PcapReadStats st;
  const auto ds = readUdpDatagrams(path, 0, &err, &st);
  ASSERT_EQ(ds.size(), 1u);
  EXPECT_EQ(ds[0].payload, (std::vector<uint8_t>{9, 9}));
  EXPECT_EQ(st.records, 6u);
  EXPECT_EQ(st.non_udp, 3u);
  EXPECT_EQ(st.fragments, 1u);
  EXPECT_EQ(st.truncated_records, 1u);
  EXPECT_TRUE(err.empty());
  std::remove(path.c_str());
}

TEST(PcapErrors, PortFilterAndRealCaptureCounts) {
  const std::string path = std::string(ROADSLAM_SHARED_DATA) +
                           "/velodyne/mrpt_sample_velodyne_vlp16_gps.pcap";
  if (!std::ifstream(path)) GTEST_SKIP() << "missing " << path;
  PcapReadStats st;
  std::string err;
  // MANIFEST.txt: 293 data packets (1206 B) + 57 position packets (512 B).
  const auto data = readUdpDatagrams(path, 2368, &err, &st);
  EXPECT_EQ(data.size(), 293u);
  for (const auto& d : data) EXPECT_EQ(d.payload.size(), 1206u);
  EXPECT_EQ(st.datagrams, 350u);
  EXPECT_EQ(readUdpDatagrams(path, 8308).size(), 57u);
  EXPECT_TRUE(err.empty()) << err;
}

#pragma once
// Byte-by-byte builders of capture files and frames, written independently of the library under test.
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <unistd.h>

namespace roadslam::pcap::test {

inline std::string tempPath(const std::string& name) {
  return std::string(ROADSLAM_BINARY_DIR) + "/pcap_test_" + std::to_string(::getpid()) + "_" + name;
}

inline std::vector<uint8_t> readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

inline void le32(std::vector<uint8_t>& v, uint32_t x) {
  for (int i = 0; i < 4; ++i) v.push_back(static_cast<uint8_t>(x >> (8 * i)));
}
inline void be16(std::vector<uint8_t>& v, uint16_t x) {
  v.push_back(static_cast<uint8_t>(x >> 8));
  v.push_back(static_cast<uint8_t>(x));
}

/// Classic pcap, record i stamped 100 + i s + 2*i us.
inline void writeClassicPcap(const std::string& path, uint32_t linktype,
                             const std::vector<std::vector<uint8_t>>& frames) {
  std::vector<uint8_t> b;
  le32(b, 0xA1B2C3D4u);
  b.push_back(2); b.push_back(0); b.push_back(4); b.push_back(0);
  le32(b, 0); le32(b, 0); le32(b, 65535); le32(b, linktype);
  uint32_t i = 0;
  for (const auto& f : frames) {
    le32(b, 100 + i); le32(b, 2 * i); le32(b, f.size()); le32(b, f.size());
    b.insert(b.end(), f.begin(), f.end());
    ++i;
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), b.size());
}

inline std::vector<uint8_t> ipv4Udp(const std::vector<uint8_t>& payload, uint16_t sport,
                                    uint16_t dport, uint8_t proto = 17, uint16_t frag = 0x4000) {
  std::vector<uint8_t> v = {0x45, 0};
  be16(v, static_cast<uint16_t>(28 + payload.size()));
  be16(v, 1); be16(v, frag);
  v.push_back(64); v.push_back(proto); be16(v, 0);
  for (uint8_t x : {192, 168, 1, 201, 255, 255, 255, 255}) v.push_back(x);
  be16(v, sport); be16(v, dport); be16(v, static_cast<uint16_t>(8 + payload.size())); be16(v, 0);
  v.insert(v.end(), payload.begin(), payload.end());
  return v;
}

inline std::vector<uint8_t> ethernet(uint16_t first_type, int vlan_tags = 0) {
  std::vector<uint8_t> v(12, 0x11);
  for (int i = 0; i < vlan_tags; ++i) { be16(v, first_type); be16(v, 0x0005); }
  be16(v, 0x0800);
  if (vlan_tags == 0) { v.resize(12); be16(v, first_type); }
  return v;
}
inline std::vector<uint8_t> sll(uint16_t proto) {
  std::vector<uint8_t> v(14, 0);
  be16(v, proto);
  return v;
}
inline std::vector<uint8_t> sll2(uint16_t proto) {
  std::vector<uint8_t> v;
  be16(v, proto);
  v.resize(20, 0);
  return v;
}

}  // namespace roadslam::pcap::test

#pragma once
// Real-format Velodyne payloads for tests (VLP-16 manual 63-9243, section 9): block flags,
// azimuths, seeded random ranges, the us-past-the-hour counter, return mode and product bytes.
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "roadslam/velodyne/packet.h"

namespace roadslam::sources::test_support {

inline std::vector<uint8_t> makeDataPacket(uint32_t t_us, uint16_t azimuth_cdeg, uint32_t seed,
                                           uint8_t mode = 0x37, uint8_t product = 0x22) {
  std::vector<uint8_t> p(velodyne::kDataPacketSize, 0);
  std::mt19937 rng(seed);
  for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) {
    uint8_t* blk = p.data() + b * 100;
    blk[0] = 0xFF;
    blk[1] = 0xEE;
    const uint16_t az = uint16_t((azimuth_cdeg + b * 40) % 36000);
    blk[2] = uint8_t(az & 0xFF);
    blk[3] = uint8_t(az >> 8);
    for (int i = 4; i < 100; ++i) blk[i] = uint8_t(rng());
  }
  for (int i = 0; i < 4; ++i) p[1200 + i] = uint8_t(t_us >> (8 * i));
  p[1204] = mode;
  p[1205] = product;
  return p;
}

/// A position packet with a $GPRMC sentence (checksum computed) at byte 206.
inline std::vector<uint8_t> makePositionPacket(uint32_t t_us, const std::string& body) {
  std::vector<uint8_t> p(velodyne::kPositionPacketSize, 0);
  for (int i = 0; i < 4; ++i) p[198 + i] = uint8_t(t_us >> (8 * i));
  uint8_t cs = 0;
  for (char c : body) cs ^= uint8_t(c);
  char tail[8];
  std::snprintf(tail, sizeof tail, "*%02X\r\n", cs);
  const std::string s = "$" + body + tail;
  std::copy(s.begin(), s.end(), p.begin() + 206);
  return p;
}

// Almeria fix of the MRPT sample capture (its MANIFEST): 36deg49.748'N 002deg24.454'W.
inline const char* kAlmeriaRmc = "GPRMC,081802,A,3649.7480,N,00224.4540,W,000.0,000.0,210116,000.0,E";
constexpr double kAlmeriaLat_deg = 36.0 + 49.748 / 60.0;
constexpr double kAlmeriaLon_deg = -(2.0 + 24.454 / 60.0);

}  // namespace roadslam::sources::test_support

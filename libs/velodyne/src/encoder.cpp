#include "roadslam/velodyne/encoder.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace roadslam::velodyne {
namespace {

void putU16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v & 0xFF);
  p[1] = static_cast<uint8_t>(v >> 8);
}

void putU32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>((v >> (8 * i)) & 0xFF);
}

uint16_t encodeRange(float range_m) {
  const double units = std::round(static_cast<double>(range_m) / kDistanceUnit_m);
  if (!(range_m > 0) || units > 65535.0) return 0;  // "no return"
  return static_cast<uint16_t>(units);
}

uint16_t encodeAzimuth(double azimuth_deg) {
  double a = std::fmod(azimuth_deg, 360.0);
  if (a < 0) a += 360.0;
  long units = std::lround(a * 100.0);
  if (units >= 36000) units -= 36000;
  return static_cast<uint16_t>(units);
}

/// Writes one 100-byte block: flag, azimuth, two 16-laser sequences (channels 0-15, 16-31).
void writeBlock(uint8_t* blk, double azimuth_deg,
                const std::array<LaserReturn, kVlp16Lasers>& first,
                const std::array<LaserReturn, kVlp16Lasers>& second) {
  putU16(blk, kBlockFlag);
  putU16(blk + 2, encodeAzimuth(azimuth_deg));
  for (int half = 0; half < 2; ++half) {
    const auto& returns = half == 0 ? first : second;
    for (int l = 0; l < kVlp16Lasers; ++l) {
      uint8_t* ch = blk + 4 + 3 * (half * kVlp16Lasers + l);
      putU16(ch, encodeRange(returns[l].range_m));
      ch[2] = returns[l].intensity;
    }
  }
}

}  // namespace

DataPacketBytes encodeVlp16Packet(const std::array<FiringSequence, kVlp16SequencesPerPacket>& seq,
                                  uint32_t timestamp_us, ReturnMode mode, Model product) {
  DataPacketBytes pkt{};
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    uint8_t* blk = pkt.data() + b * kBlockSize;
    if (mode == ReturnMode::Dual) {
      // Manual 9.3.2.2: block 2j holds the last returns, block 2j+1 the strongest, same azimuth.
      const int s = 2 * (b / 2);
      const bool last = (b % 2) == 0;
      writeBlock(blk, seq[s].azimuth_deg, last ? seq[s].last : seq[s].strongest,
                 last ? seq[s + 1].last : seq[s + 1].strongest);
    } else {
      const int s = 2 * b;
      const bool last = mode == ReturnMode::Last;
      writeBlock(blk, seq[s].azimuth_deg, last ? seq[s].last : seq[s].strongest,
                 last ? seq[s + 1].last : seq[s + 1].strongest);
    }
  }
  putU32(pkt.data() + kTimestampOffset, timestamp_us);
  pkt[kReturnModeOffset] = static_cast<uint8_t>(mode);
  pkt[kProductIdOffset] = static_cast<uint8_t>(product);
  return pkt;
}

DataPacketBytes encodeHdl32Packet(const std::array<Hdl32Firing, kBlocksPerPacket>& firings, uint32_t timestamp_us,
                                  ReturnMode mode, Model product) {
  DataPacketBytes pkt{};
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    uint8_t* blk = pkt.data() + b * kBlockSize;
    putU16(blk, kBlockFlag);
    putU16(blk + 2, encodeAzimuth(firings[b].azimuth_deg));
    for (int c = 0; c < kHdl32Lasers; ++c) {
      uint8_t* ch = blk + 4 + 3 * c;
      putU16(ch, encodeRange(firings[b].returns[c].range_m));
      ch[2] = firings[b].returns[c].intensity;
    }
  }
  putU32(pkt.data() + kTimestampOffset, timestamp_us);
  pkt[kReturnModeOffset] = static_cast<uint8_t>(mode);
  pkt[kProductIdOffset] = static_cast<uint8_t>(product);
  return pkt;
}

std::array<uint8_t, kPositionPacketSize> encodePositionPacket(uint32_t timestamp_us,
                                                              const char* nmea) {
  // Manual 9.4 / MRPT TVelodynePositionPacket: u32 timestamp at byte 198, NMEA sentence at 206.
  std::array<uint8_t, kPositionPacketSize> pkt{};
  putU32(pkt.data() + kPositionTimestampOffset, timestamp_us);
  pkt[kPositionTimestampOffset + 4] = 2;  // PPS status: locked
  if (nmea != nullptr) {
    const std::size_t room = kPositionPacketSize - kPositionNmeaOffset - 1;
    const std::size_t n = std::min(std::strlen(nmea), room);
    std::memcpy(pkt.data() + kPositionNmeaOffset, nmea, n);
  }
  return pkt;
}

}  // namespace roadslam::velodyne

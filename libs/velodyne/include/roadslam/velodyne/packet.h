#pragma once
/// \file packet.h
/// Velodyne VLP-16 / HDL-32E UDP packet layout (VLP-16 User Manual 63-9243 Rev. E, section 9;
/// HDL-32E User Manual 63-9113, appendix E). All fields little-endian.
///
/// Data packet, 1206-byte UDP payload on port 2368:
///   12 blocks x 100 bytes: u16 flag 0xEEFF, u16 azimuth [0.01 deg],
///                          32 x { u16 distance [2 mm units], u8 reflectivity }
///   u32 timestamp [us past the top of the hour], u8 return mode, u8 product id
/// VLP-16: each block holds two firing sequences of 16 lasers (channels 0-15, 16-31).
/// Position packet, 512-byte UDP payload on port 8308, NMEA $GPRMC sentence at byte 206.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace roadslam::velodyne {

constexpr std::size_t kDataPacketSize = 1206;
constexpr std::size_t kPositionPacketSize = 512;
constexpr int kBlocksPerPacket = 12;
constexpr int kChannelsPerBlock = 32;
constexpr uint16_t kBlockFlag = 0xEEFF;
constexpr std::size_t kBlockSize = 100;  ///< bytes per data block: flag, azimuth, 32 channels x 3
/// u32 timestamp, u8 return mode, u8 product id after the 12 blocks (byte 1200)
constexpr std::size_t kTailOffset = kBlocksPerPacket * kBlockSize;
constexpr std::size_t kTimestampOffset = kTailOffset;       ///< u32 [us past the top of the hour]
constexpr std::size_t kReturnModeOffset = kTailOffset + 4;  ///< u8 ReturnMode
constexpr std::size_t kProductIdOffset = kTailOffset + 5;   ///< u8 Model (product id)
constexpr double kDistanceUnit_m = 0.002;  ///< a channel's distance in 2 mm units (manual 9.3.1.3)
constexpr double kAzimuthUnit_deg = 0.01;  ///< a block's azimuth in 0.01 deg units
constexpr uint16_t kDefaultDataPort = 2368;
constexpr uint16_t kDefaultPositionPort = 8308;
constexpr std::size_t kPositionTimestampOffset = 198;  ///< u32 [us past the hour] in a position packet
constexpr std::size_t kPositionNmeaOffset = 206;       ///< NUL-padded NMEA sentence in a position packet

// VLP-16 firing timing (manual, section 9.5): one laser every 2.304 us, a 16-laser sequence
// (with recharge) every 55.296 us, so one packet spans 24 sequences = 1327.104 us (754 packets/s).
constexpr double kVlp16LaserPeriod_s = 2.304e-6;
constexpr double kVlp16SequencePeriod_s = 55.296e-6;
constexpr int kVlp16Lasers = 16;
constexpr int kVlp16SequencesPerPacket = 24;
// HDL-32E: 32 lasers fired every 1.152 us, a block every 46.080 us.
constexpr double kHdl32LaserPeriod_s = 1.152e-6;
constexpr double kHdl32BlockPeriod_s = 46.080e-6;
constexpr int kHdl32Lasers = 32;

enum class ReturnMode : uint8_t { Strongest = 0x37, Last = 0x38, Dual = 0x39 };
enum class Model : uint8_t { Unknown = 0, VLP16 = 0x22, HDL32 = 0x21 };

using DataPacketBytes = std::array<uint8_t, kDataPacketSize>;

/// Block-to-block azimuth advance of one packet [0.01 deg] from its 12 block azimuths [0.01 deg]:
/// element 6 of the 11 sorted differences (as VeloView), which skips the zero steps of dual-return
/// block pairs and one wrap outlier.
int blockAzimuthStep(const std::array<uint16_t, kBlocksPerPacket>& azimuth);

/// A UDP payload as received or read from a capture, with the clock it arrived on.
struct RawPacket {
  double stamp_s = 0;      ///< capture / kernel receive time [s since epoch]
  uint16_t dst_port = 0;   ///< UDP destination port (2368 data, 8308 position by default)
  uint32_t src_ip = 0;     ///< IPv4 source address, host byte order (0 when unknown)
  std::vector<uint8_t> payload;
};

}  // namespace roadslam::velodyne

#pragma once
/// \file position.h
/// Velodyne position packets (512-byte UDP payload, port 8308; VLP-16 manual 9.4) and the NMEA
/// $GPRMC sentence they carry, read by libs/gnss's NMEA parser (gnss::parseRmc).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "roadslam/gnss/nmea.h"

namespace roadslam::velodyne {

struct PositionPacket {
  uint32_t timestamp_us = 0;  ///< sensor time [us past the hour]
  std::string nmea;           ///< the NMEA sentence (may be empty: no GPS attached)
  /// The sentence's RMC with its position, valid or not (fix->valid()); nullopt when the sentence is
  /// empty, not RMC or malformed. Its t_receive_s is NaN: the packet's receive time is the caller's.
  std::optional<gnss::GnssFix> fix;
};

/// Decodes a 512-byte position packet; false when the size is wrong.
bool decodePositionPacket(const uint8_t* data, std::size_t size, PositionPacket& out) noexcept;

}  // namespace roadslam::velodyne

#pragma once
/// \file position.h
/// Velodyne position packets (512-byte UDP payload, port 8308; VLP-16 manual 9.4) and the NMEA
/// $GPRMC sentence they carry (NMEA 0183: hhmmss.ss,A|V,ddmm.mmmm,N|S,dddmm.mmmm,E|W,knots,
/// course deg,ddmmyy,...*checksum).

#include <cstddef>
#include <cstdint>
#include <string>

namespace roadslam::velodyne {

struct GpsFix {
  bool valid = false;       ///< RMC status 'A' (a 'V' fix still parses, with valid = false)
  double time_of_day_s = 0; ///< UTC seconds since midnight [s]
  int year = 0, month = 0, day = 0;  ///< UTC date (0 when the field is empty)
  double latitude_deg = 0;  ///< WGS84 latitude, north positive [deg]
  double longitude_deg = 0; ///< WGS84 longitude, east positive [deg]
  double speed_mps = 0;     ///< speed over ground [m/s] (from knots)
  double course_rad = 0;    ///< track made good, clockwise from true north [rad]
  /// UTC time since the Unix epoch [s]; NaN without a date.
  double epochSeconds() const;
};

/// Parses one $GPRMC / $GNRMC sentence; false when it is not RMC, its checksum is wrong, or a
/// field is malformed. Never throws.
bool parseRmc(const std::string& sentence, GpsFix& fix) noexcept;

struct PositionPacket {
  uint32_t timestamp_us = 0;  ///< sensor time [us past the hour]
  std::string nmea;           ///< the NMEA sentence (may be empty: no GPS attached)
  bool has_fix = false;       ///< nmea parsed as RMC (valid or not: see fix.valid)
  GpsFix fix;
};

/// Decodes a 512-byte position packet; false when the size is wrong.
bool decodePositionPacket(const uint8_t* data, std::size_t size, PositionPacket& out) noexcept;

}  // namespace roadslam::velodyne

#pragma once
/// \file gps_fix.h
/// A GPS fix taken from the $GPRMC sentence a Velodyne sensor forwards in its position packets.

#include <optional>
#include <string>

#include "roadslam/velodyne/packet.h"

namespace roadslam::sources {

struct GpsFix {
  double stamp_s = 0;       ///< host/capture time of the position packet [s since epoch]
  double utc_s = 0;         ///< UTC time of day from the sentence [s past midnight]
  bool valid = false;       ///< RMC status 'A' (the receiver had a fix)
  double latitude_deg = 0;  ///< WGS84 latitude, north positive [deg]
  double longitude_deg = 0; ///< WGS84 longitude, east positive [deg]
  double speed_mps = 0;     ///< ground speed [m/s] (sentence carries knots)
  double course_deg = 0;    ///< track over ground, clockwise from true north [deg]
  std::string nmea;         ///< the sentence as received, without CR/LF
};

/// The NMEA text of a 512-byte position packet (bytes 206.., NUL-terminated; VLP-16 manual 9.4),
/// without trailing CR/LF; empty when the packet carries none (early VLP-16 firmware).
std::string nmeaOfPositionPacket(const velodyne::RawPacket& pkt);

/// Parses the $GPRMC/$GNRMC sentence of a position packet with MRPT's NMEA parser
/// (mrpt::hwdrivers::CGPSInterface::parse_NMEA); nullopt when there is no RMC sentence.
std::optional<GpsFix> parseGpsFix(const velodyne::RawPacket& pkt);

}  // namespace roadslam::sources

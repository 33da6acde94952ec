#pragma once
/// \file gps_fix.h
/// A GPS fix with the time it was received: the $GPRMC sentence a Velodyne forwards in its
/// position packets (decoded by libs/velodyne's position.h), or an MRPT CObservationGPS record.

#include <limits>
#include <optional>

#include "roadslam/velodyne/packet.h"
#include "roadslam/velodyne/position.h"

namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam::sources {

struct TimedGpsFix {
  double stamp_s = 0;      ///< capture / receive time of the position packet [s since epoch]
  velodyne::GpsFix fix;    ///< the RMC content (valid flag, WGS84 position, speed, course)
  /// From an NMEA GGA when the record has one (a GNSS receiver's epoch, a car's CAN_GPS); a GGA
  /// without RMC also gives the position, time of day and validity (quality > 0).
  double h_m = std::numeric_limits<double>::quiet_NaN();   ///< height: GGA altitude + geoid separation [m]
  double hdop = std::numeric_limits<double>::quiet_NaN();  ///< [-]
  int quality = -1;                                        ///< GGA fix quality; -1 without GGA
};

/// Decodes a 512-byte position packet; nullopt when it holds no RMC sentence (early VLP-16
/// firmware sends an empty NMEA field) or the sentence is malformed.
std::optional<TimedGpsFix> decodeGpsFix(const velodyne::RawPacket& pkt);

/// A CObservationGPS record's fix: its GGA (position, height, HDOP, quality) and RMC (date, speed,
/// course), stamped with the receive time (originalReceivedTimestamp, else timestamp).
TimedGpsFix gpsFixFromObservation(const mrpt::obs::CObservationGPS& o);

}  // namespace roadslam::sources

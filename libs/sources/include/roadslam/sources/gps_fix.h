#pragma once
/// \file gps_fix.h
/// A GPS fix with the time it was received: the $GPRMC sentence a Velodyne forwards in its
/// position packets (decoded by libs/velodyne's position.h), or an MRPT CObservationGPS record.

#include <cstddef>
#include <limits>
#include <map>
#include <optional>
#include <string>

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
  /// The sensor it came from: a CObservationGPS record's sensorLabel (roadslam-grab's
  /// `<lidar>_GPS`, a receiver's `[gnss] label`, `CAN_GPS`), kPositionPacketsLabel for a capture's
  /// Velodyne position packets.
  std::string label;
};

/// TimedGpsFix::label of the fixes a .pcap's Velodyne position packets carry (a capture has no
/// sensorLabel; it holds one Velodyne).
inline const char* const kPositionPacketsLabel = "position_packets";

/// Decodes a 512-byte position packet; nullopt when it holds no RMC sentence (early VLP-16
/// firmware sends an empty NMEA field) or the sentence is malformed.
std::optional<TimedGpsFix> decodeGpsFix(const velodyne::RawPacket& pkt);

/// A CObservationGPS record's fix: its GGA (position, height, HDOP, quality) and RMC (date, speed,
/// course), stamped with the receive time (originalReceivedTimestamp, else timestamp).
TimedGpsFix gpsFixFromObservation(const mrpt::obs::CObservationGPS& o);

/// The GPS sources of the recording \p path, by TimedGpsFix::label: a rawlog's or a roadslam-grab
/// session folder's CObservationGPS records counted per sensorLabel (from each file's index,
/// rawlog_index.h; a fresh sidecar is read, none is written); a .pcap gives {kPositionPacketsLabel, 0}
/// (0: not counted); a KITTI folder or anything else, none. Throws naming the file when a rawlog
/// cannot be read at all.
std::map<std::string, std::size_t> gpsSourcesOf(const std::string& path);

}  // namespace roadslam::sources

#pragma once
/// \file gps_fix.h
/// The GPS fixes a recording carries, as gnss::GnssFix (libs/gnss, the one GNSS fix type): the $GPRMC
/// sentence a Velodyne forwards in its position packets, or an MRPT CObservationGPS record. Their
/// t_receive_s is the capture / receive time, their label the sensor they came from.

#include <cstddef>
#include <map>
#include <optional>
#include <string>

#include "roadslam/gnss/nmea.h"
#include "roadslam/velodyne/packet.h"

namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam::sources {

/// GnssFix::label of the fixes a .pcap's Velodyne position packets carry (a capture has no
/// sensorLabel; it holds one Velodyne).
inline const char* const kPositionPacketsLabel = "position_packets";

/// Decodes a 512-byte position packet received at pkt.stamp_s (t_receive_s); nullopt when it holds
/// no RMC sentence with a position (early VLP-16 firmware sends an empty NMEA field) or the sentence
/// is malformed.
std::optional<gnss::GnssFix> decodeGpsFix(const velodyne::RawPacket& pkt);

/// A CObservationGPS record's fix: its GGA (position, height, HDOP, quality) and RMC (status, date,
/// speed, course; its position over the GGA's), received at originalReceivedTimestamp, else timestamp.
/// Without a GGA, position.h_m is 0 and hdop NaN.
gnss::GnssFix gpsFixFromObservation(const mrpt::obs::CObservationGPS& o);

/// The GPS sources of the recording \p path, by GnssFix::label: a rawlog's or a roadslam-grab
/// session folder's CObservationGPS records counted per sensorLabel (from each file's index,
/// rawlog_index.h; a fresh sidecar is read, none is written); a .pcap gives {kPositionPacketsLabel, 0}
/// (0: not counted); a KITTI folder or anything else, none. Throws naming the file when a rawlog
/// cannot be read at all.
std::map<std::string, std::size_t> gpsSourcesOf(const std::string& path);

}  // namespace roadslam::sources

#pragma once
/// \file gps_observation.h
/// A GNSS fix as the standard MRPT observation (CObservationGPS with NMEA messages), filled from our
/// NMEA decoder (libs/gnss) so no MRPT hardware-driver library is needed.

#include <string>

#include "roadslam/gnss/nmea.h"

namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam::rawlog {

/// Fills \p out with the RMC message of \p fix (a Velodyne position packet's sentence: status,
/// position, speed, course, date) received at \p stamp_s [s since epoch] under \p label; both
/// timestamps are \p stamp_s.
void fillRmcObservation(const gnss::GnssFix& fix, double stamp_s, const std::string& label,
                        mrpt::obs::CObservationGPS& out);

/// Fills \p out with a receiver epoch read from NMEA (libs/gnss): an NMEA GGA message (quality,
/// satellites, HDOP, altitude) when the epoch had a GGA or a position, RMC when it had an RMC, VTG with
/// its speed and course. CObservation::timestamp is the receiver's UTC time (has_satellite_timestamp)
/// or, before the first RMC date, the receive time; originalReceivedTimestamp is the host receive time.
/// MRPT 2.5 has no GST message: the GST sigmas are not kept (the NMEA log keeps them).
void fillGnssObservation(const gnss::GnssFix& fix, const std::string& label, mrpt::obs::CObservationGPS& out);

}  // namespace roadslam::rawlog

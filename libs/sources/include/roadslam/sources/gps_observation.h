#pragma once
/// \file gps_observation.h
/// A decoded $GPRMC fix as the standard MRPT observation (CObservationGPS with an NMEA RMC message),
/// filled from our NMEA decoder so no MRPT hardware-driver library is needed.

#include <string>

#include "roadslam/gnss/nmea.h"
#include "roadslam/velodyne/position.h"

namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam::sources {

/// Fills \p out with \p fix received at \p stamp_s [s since epoch] under \p label.
void fillGpsObservation(const velodyne::GpsFix& fix, double stamp_s, const std::string& label,
                        mrpt::obs::CObservationGPS& out);

/// Fills \p out with a receiver epoch read from NMEA (libs/gnss): an NMEA GGA message (quality,
/// satellites, HDOP, altitude) when the epoch had a GGA or a position, RMC when it had an RMC, VTG with
/// its speed and course. CObservation::timestamp is the receiver's UTC time (has_satellite_timestamp)
/// or, before the first RMC date, the receive time; originalReceivedTimestamp is the host receive time.
/// MRPT 2.5 has no GST message: the GST sigmas are not kept (the NMEA log keeps them).
void fillGnssObservation(const gnss::GnssFix& fix, const std::string& label, mrpt::obs::CObservationGPS& out);

}  // namespace roadslam::sources

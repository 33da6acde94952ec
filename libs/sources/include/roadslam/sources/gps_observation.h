#pragma once
/// \file gps_observation.h
/// A decoded $GPRMC fix as the standard MRPT observation (CObservationGPS with an NMEA RMC message),
/// filled from our NMEA decoder so no MRPT hardware-driver library is needed.

#include <string>

#include "roadslam/velodyne/position.h"

namespace mrpt::obs {
class CObservationGPS;
}

namespace roadslam::sources {

/// Fills \p out with \p fix received at \p stamp_s [s since epoch] under \p label.
void fillGpsObservation(const velodyne::GpsFix& fix, double stamp_s, const std::string& label,
                        mrpt::obs::CObservationGPS& out);

}  // namespace roadslam::sources

#include "roadslam/sources/gps_observation.h"

#include <mrpt/obs/CObservationGPS.h>

#include <cmath>

namespace roadslam::sources {
namespace {
constexpr double kDeg = M_PI / 180.0;
constexpr double kKnot_mps = 1852.0 / 3600.0;  // international knot
}  // namespace

void fillGpsObservation(const velodyne::GpsFix& f, double stamp_s, const std::string& label,
                        mrpt::obs::CObservationGPS& out) {
  // The fields MRPT's NMEA parser (CGPSInterface::parse_NMEA) fills for an RMC sentence.
  mrpt::obs::gnss::Message_NMEA_RMC rmc;
  const double tod = f.time_of_day_s;
  rmc.fields.UTCTime.hour = uint8_t(tod / 3600);
  rmc.fields.UTCTime.minute = uint8_t(std::fmod(tod, 3600.0) / 60);
  rmc.fields.UTCTime.sec = std::fmod(tod, 60.0);
  rmc.fields.validity_char = f.valid ? 'A' : 'V';
  rmc.fields.latitude_degrees = f.latitude_deg;
  rmc.fields.longitude_degrees = f.longitude_deg;
  rmc.fields.speed_knots = f.speed_mps / kKnot_mps;
  rmc.fields.direction_degrees = f.course_rad / kDeg;
  rmc.fields.date_day = uint8_t(f.day);
  rmc.fields.date_month = uint8_t(f.month);
  rmc.fields.date_year = uint8_t(f.year % 100);
  out.setMsg(rmc);
  out.sensorLabel = label;
  out.timestamp = mrpt::Clock::fromDouble(stamp_s);
  out.originalReceivedTimestamp = out.timestamp;
}

}  // namespace roadslam::sources

#include "roadslam/rawlog/gps_observation.h"

#include <mrpt/obs/CObservationGPS.h>

#include "roadslam/common/param_table.h"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace roadslam::rawlog {
namespace {
using unit::kDeg;
using unit::kKnot;

mrpt::obs::gnss::UTC_time utcOf(double time_of_day_s) {
  const double tod = std::isfinite(time_of_day_s) ? time_of_day_s : 0.0;
  mrpt::obs::gnss::UTC_time utc;
  utc.hour = uint8_t(tod / 3600);
  utc.minute = uint8_t(std::fmod(tod, 3600.0) / 60);
  utc.sec = std::fmod(tod, 60.0);
  return utc;
}

/// The fields MRPT's NMEA parser (CGPSInterface::parse_NMEA) fills for an RMC sentence; an empty
/// speed or course field is 0 there, and the date comes from the receiver's UTC time when known.
mrpt::obs::gnss::Message_NMEA_RMC rmcOf(const gnss::GnssFix& f) {
  mrpt::obs::gnss::Message_NMEA_RMC rmc;
  rmc.fields.UTCTime = utcOf(f.time_of_day_s);
  rmc.fields.validity_char = f.rmc_status;
  rmc.fields.latitude_degrees = f.position.lat_deg;
  rmc.fields.longitude_degrees = f.position.lon_deg;
  rmc.fields.speed_knots = std::isfinite(f.speed_mps) ? f.speed_mps / kKnot : 0.0;
  rmc.fields.direction_degrees = std::isfinite(f.course_rad) ? f.course_rad / kDeg : 0.0;
  if (std::isfinite(f.t_receiver_s)) {
    const auto secs = static_cast<std::time_t>(std::floor(f.t_receiver_s));
    std::tm tm{};
    gmtime_r(&secs, &tm);
    rmc.fields.date_day = uint8_t(tm.tm_mday);
    rmc.fields.date_month = uint8_t(tm.tm_mon + 1);
    rmc.fields.date_year = uint8_t(tm.tm_year % 100);
  }
  return rmc;
}
}  // namespace

void fillRmcObservation(const gnss::GnssFix& f, double stamp_s, const std::string& label,
                        mrpt::obs::CObservationGPS& out) {
  out.setMsg(rmcOf(f));
  out.sensorLabel = label;
  out.timestamp = mrpt::Clock::fromDouble(stamp_s);
  out.originalReceivedTimestamp = out.timestamp;
}

void fillGnssObservation(const gnss::GnssFix& f, const std::string& label, mrpt::obs::CObservationGPS& out) {
  const mrpt::obs::gnss::UTC_time utc = utcOf(f.time_of_day_s);
  if (f.quality >= 0 || f.has_position) {
    mrpt::obs::gnss::Message_NMEA_GGA gga;
    gga.fields.UTCTime = utc;
    gga.fields.latitude_degrees = f.position.lat_deg;
    gga.fields.longitude_degrees = f.position.lon_deg;
    gga.fields.fix_quality = uint8_t(f.quality >= 0 ? f.quality : (f.valid() ? 1 : 0));
    gga.fields.altitude_meters = f.position.h_m;  // ellipsoidal (altitude + separation of the sentence)
    gga.fields.geoidal_distance = 0;
    gga.fields.orthometric_altitude = f.position.h_m;
    gga.fields.satellitesUsed = uint32_t(std::max(0, f.satellites));
    gga.fields.thereis_HDOP = std::isfinite(f.hdop);
    gga.fields.HDOP = std::isfinite(f.hdop) ? float(f.hdop) : 0.f;
    out.setMsg(gga);
  }
  if (f.rmc_status != 0) out.setMsg(rmcOf(f));
  if (std::isfinite(f.speed_mps) || std::isfinite(f.course_rad)) {
    mrpt::obs::gnss::Message_NMEA_VTG vtg;
    vtg.fields.true_track = std::isfinite(f.course_rad) ? f.course_rad / kDeg : 0.0;
    vtg.fields.ground_speed_knots = std::isfinite(f.speed_mps) ? f.speed_mps / kKnot : 0.0;
    vtg.fields.ground_speed_kmh = std::isfinite(f.speed_mps) ? f.speed_mps * 3.6 : 0.0;
    out.setMsg(vtg);
  }
  out.sensorLabel = label;
  out.has_satellite_timestamp = std::isfinite(f.t_receiver_s);
  out.timestamp = mrpt::Clock::fromDouble(out.has_satellite_timestamp ? f.t_receiver_s : f.t_receive_s);
  out.originalReceivedTimestamp = mrpt::Clock::fromDouble(std::isfinite(f.t_receive_s) ? f.t_receive_s : f.t_receiver_s);
}

}  // namespace roadslam::rawlog

#include "roadslam/sources/gps_fix.h"

#include <mrpt/hwdrivers/CGPSInterface.h>
#include <mrpt/obs/CObservationGPS.h>

#include <algorithm>

namespace roadslam::sources {
namespace {
constexpr std::size_t kNmeaOffset = 206;       // VLP-16 manual 63-9243, table 9-5
constexpr double kKnot_mps = 1852.0 / 3600.0;  // international knot
}  // namespace

std::string nmeaOfPositionPacket(const velodyne::RawPacket& pkt) {
  if (pkt.payload.size() <= kNmeaOffset) return {};
  const auto begin = pkt.payload.begin() + kNmeaOffset;
  const auto end = std::find(begin, pkt.payload.end(), uint8_t(0));
  std::string s(begin, end);
  while (!s.empty() && (s.back() == '\r' || s.back() == '\n')) s.pop_back();
  return s;
}

std::optional<GpsFix> parseGpsFix(const velodyne::RawPacket& pkt) {
  GpsFix fix;
  fix.nmea = nmeaOfPositionPacket(pkt);
  if (fix.nmea.size() < 6 || fix.nmea.compare(3, 3, "RMC") != 0) return std::nullopt;
  mrpt::obs::CObservationGPS obs;
  if (!mrpt::hwdrivers::CGPSInterface::parse_NMEA(fix.nmea, obs) ||
      !obs.hasMsgClass<mrpt::obs::gnss::Message_NMEA_RMC>())
    return std::nullopt;
  const auto& f = obs.getMsgByClass<mrpt::obs::gnss::Message_NMEA_RMC>().fields;
  fix.stamp_s = pkt.stamp_s;
  fix.utc_s = f.UTCTime.hour * 3600.0 + f.UTCTime.minute * 60.0 + f.UTCTime.sec;
  fix.valid = f.validity_char == 'A';
  fix.latitude_deg = f.latitude_degrees;
  fix.longitude_deg = f.longitude_degrees;
  fix.speed_mps = f.speed_knots * kKnot_mps;
  fix.course_deg = f.direction_degrees;
  return fix;
}

}  // namespace roadslam::sources

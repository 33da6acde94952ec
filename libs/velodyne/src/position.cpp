#include "roadslam/velodyne/position.h"

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <limits>
#include <vector>

#include "roadslam/velodyne/packet.h"

namespace roadslam::velodyne {
namespace {

constexpr double kKnot_mps = 1852.0 / 3600.0;

bool toDouble(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

/// NMEA "ddmm.mmmm" / "dddmm.mmmm" -> degrees.
bool toDegrees(const std::string& s, double& deg) {
  double v = 0;
  if (!toDouble(s, v) || v < 0) return false;
  const double whole = std::floor(v / 100.0);
  const double minutes = v - whole * 100.0;
  if (minutes >= 60.0) return false;
  deg = whole + minutes / 60.0;
  return true;
}

bool checksumOk(const std::string& s, std::size_t& body_end) {
  body_end = s.find('*');
  if (body_end == std::string::npos) {
    body_end = s.size();
    return true;  // checksum is optional in NMEA 0183
  }
  if (body_end + 3 > s.size()) return false;
  unsigned x = 0;
  for (std::size_t i = 1; i < body_end; ++i) x ^= static_cast<unsigned char>(s[i]);
  const std::string hex = s.substr(body_end + 1, 2);
  char* end = nullptr;
  const unsigned long want = std::strtoul(hex.c_str(), &end, 16);
  return end == hex.c_str() + 2 && want == x;
}

bool parseFields(const std::vector<std::string>& f, GpsFix& fix) {
  if (f.size() < 10) return false;
  double hms = 0;
  if (!toDouble(f[1], hms)) return false;
  const double hh = std::floor(hms / 10000.0), mm = std::floor((hms - hh * 10000.0) / 100.0);
  fix.time_of_day_s = hh * 3600.0 + mm * 60.0 + (hms - hh * 10000.0 - mm * 100.0);
  fix.valid = f[2] == "A";
  if (!fix.valid && f[2] != "V") return false;
  if (!toDegrees(f[3], fix.latitude_deg) || !toDegrees(f[5], fix.longitude_deg)) return false;
  if (f[4] == "S") fix.latitude_deg = -fix.latitude_deg;
  else if (f[4] != "N") return false;
  if (f[6] == "W") fix.longitude_deg = -fix.longitude_deg;
  else if (f[6] != "E") return false;
  double knots = 0, course = 0;
  fix.speed_mps = toDouble(f[7], knots) ? knots * kKnot_mps : 0.0;
  fix.course_rad = toDouble(f[8], course) ? course * M_PI / 180.0 : 0.0;
  if (f[9].size() == 6) {
    const int d = std::atoi(f[9].c_str());
    fix.day = d / 10000;
    fix.month = (d / 100) % 100;
    fix.year = 2000 + d % 100;  // RMC carries a two-digit year
  }
  return true;
}

}  // namespace

double GpsFix::epochSeconds() const {
  if (year == 0) return std::numeric_limits<double>::quiet_NaN();
  std::tm t{};
  t.tm_year = year - 1900;
  t.tm_mon = month - 1;
  t.tm_mday = day;
  return static_cast<double>(timegm(&t)) + time_of_day_s;
}

bool parseRmc(const std::string& sentence, GpsFix& fix) noexcept {
  try {
    if (sentence.size() < 7 || sentence[0] != '$' || sentence.compare(3, 3, "RMC") != 0)
      return false;
    std::size_t body_end = 0;
    if (!checksumOk(sentence, body_end)) return false;
    std::vector<std::string> fields(1);
    for (std::size_t i = 0; i < body_end; ++i) {
      if (sentence[i] == ',') fields.emplace_back();
      else fields.back().push_back(sentence[i]);
    }
    GpsFix out;
    if (!parseFields(fields, out)) return false;
    fix = out;
    return true;
  } catch (...) {
    return false;  // allocation failure only
  }
}

bool decodePositionPacket(const uint8_t* data, std::size_t size, PositionPacket& out) noexcept {
  if (data == nullptr || size != kPositionPacketSize) return false;
  const uint8_t* ts = data + kPositionTimestampOffset;
  out.timestamp_us = uint32_t{ts[0]} | (uint32_t{ts[1]} << 8) | (uint32_t{ts[2]} << 16) |
                     (uint32_t{ts[3]} << 24);
  try {
    out.nmea.clear();
    for (std::size_t i = kPositionNmeaOffset; i < size; ++i) {
      const char c = static_cast<char>(data[i]);
      if (c == '\0' || c == '\r' || c == '\n') break;
      out.nmea.push_back(c);
    }
  } catch (...) {
    return false;
  }
  out.has_fix = parseRmc(out.nmea, out.fix);
  return true;
}

}  // namespace roadslam::velodyne

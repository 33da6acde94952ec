#include "roadslam/gnss/nmea.h"

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace roadslam::gnss {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kKnot_mps = 1852.0 / 3600.0;  // international knot

std::vector<std::string> splitFields(const std::string& s) {
  std::vector<std::string> out;
  size_t a = 0;
  for (;;) {
    const size_t b = s.find(',', a);
    out.push_back(s.substr(a, b == std::string::npos ? std::string::npos : b - a));
    if (b == std::string::npos) return out;
    a = b + 1;
  }
}

bool toDouble(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

/// hhmmss.ss -> seconds of the day.
bool timeOfDay(const std::string& s, double& tod) {
  double v;
  if (s.size() < 6 || !toDouble(s, v)) return false;
  const int hh = std::atoi(s.substr(0, 2).c_str()), mm = std::atoi(s.substr(2, 2).c_str());
  const double ss = std::strtod(s.c_str() + 4, nullptr);
  if (hh > 23 || mm > 59 || ss >= 61) return false;
  tod = hh * 3600.0 + mm * 60.0 + ss;
  return true;
}

/// (d)ddmm.mmmm + hemisphere -> signed degrees; \p deg_digits 2 for latitude, 3 for longitude.
bool angle(const std::string& v, const std::string& hemi, int deg_digits, double& out) {
  double x;
  if (static_cast<int>(v.size()) < deg_digits + 2 || !toDouble(v, x) || hemi.size() != 1) return false;
  const double deg = std::atof(v.substr(0, static_cast<size_t>(deg_digits)).c_str());
  const double min = std::strtod(v.c_str() + deg_digits, nullptr);
  if (min >= 60) return false;
  out = deg + min / 60.0;
  const char h = hemi[0];
  if (h == 'S' || h == 'W') out = -out;
  else if (h != 'N' && h != 'E') return false;
  return out >= -180 && out <= 180;
}

/// Midnight UTC of ddmmyy [s since epoch].
bool dateEpoch(const std::string& s, double& out) {
  if (s.size() != 6) return false;
  std::tm tm{};
  tm.tm_mday = std::atoi(s.substr(0, 2).c_str());
  tm.tm_mon = std::atoi(s.substr(2, 2).c_str()) - 1;
  const int yy = std::atoi(s.substr(4, 2).c_str());
  tm.tm_year = (yy < 80 ? 2000 + yy : 1900 + yy) - 1900;
  if (tm.tm_mday < 1 || tm.tm_mday > 31 || tm.tm_mon < 0 || tm.tm_mon > 11) return false;
  out = static_cast<double>(timegm(&tm));
  return true;
}

void appendType(GnssFix& f, const std::string& type) {
  if (f.sentences.find(type) != std::string::npos) return;
  if (!f.sentences.empty()) f.sentences += ',';
  f.sentences += type;
}

std::string hhmmss(double tod) {
  tod = std::fmod(std::max(0.0, tod), 86400.0);
  const int h = static_cast<int>(tod / 3600), m = static_cast<int>(std::fmod(tod, 3600.0) / 60);
  char b[16];
  std::snprintf(b, sizeof(b), "%02d%02d%05.2f", h, m, std::fmod(tod, 60.0));
  return b;
}

std::string latLon(double v, int deg_digits, char pos, char neg) {
  const double a = std::abs(v);
  const int d = static_cast<int>(a);
  char b[40];
  std::snprintf(b, sizeof(b), deg_digits == 2 ? "%02d%011.8f,%c" : "%03d%011.8f,%c", d, (a - d) * 60.0,
                v >= 0 ? pos : neg);
  return b;
}

}  // namespace

bool GnssFix::valid() const {
  if (!has_position) return false;
  if (quality >= 0) return quality > 0;
  return rmc_status == 'A';
}

double GnssFix::stamp(bool prefer_receiver) const {
  return prefer_receiver && std::isfinite(t_receiver_s) ? t_receiver_s : t_receive_s;
}

Eigen::Matrix3d GnssFix::covarianceEnu(double uere_m, double fallback_sigma_m) const {
  Eigen::Vector3d s;
  if (std::isfinite(sigma_lat_m) && std::isfinite(sigma_lon_m) && sigma_lat_m > 0 && sigma_lon_m > 0) {
    const double alt = std::isfinite(sigma_alt_m) && sigma_alt_m > 0 ? sigma_alt_m : 2 * std::max(sigma_lat_m, sigma_lon_m);
    s << sigma_lon_m, sigma_lat_m, alt;  // ENU: east = longitude, north = latitude
  } else if (std::isfinite(hdop) && hdop > 0) {
    s << hdop * uere_m, hdop * uere_m, 2 * hdop * uere_m;
  } else {
    s.setConstant(fallback_sigma_m);
  }
  return s.cwiseProduct(s).asDiagonal();
}

std::map<std::string, uint64_t> NmeaCounters::named() const {
  return {{"lines", lines},           {"sentences", sentences},   {"epochs", epochs},
          {"fixes", fixes},           {"bad checksum", bad_checksum}, {"malformed", malformed},
          {"no fix", no_fix},         {"time backwards", time_backwards}, {"time jump", time_jumps},
          {"other datum", other_datum}, {"unsupported sentence", unsupported}};
}

void NmeaParser::problem(const std::string& what) {
  if (problems_.size() < 20) problems_.push_back("line " + std::to_string(c_.lines) + ": " + what);
}

void NmeaParser::finish(GnssFix& f) {
  ++c_.epochs;
  if (cur_dropped_) {
    f.has_position = false;  // counted as time_backwards
    f.quality = 0;
    return;
  }
  if (!cur_datum_ok_) {
    ++c_.other_datum;
    f.has_position = false;  // a position in an unknown datum is not WGS84: never used
    return;
  }
  if (!f.valid()) ++c_.no_fix;
}

std::optional<GnssFix> NmeaParser::startEpoch(double tod, double receive_s) {
  std::optional<GnssFix> done;
  if (cur_ && cur_->time_of_day_s == tod) return done;
  if (cur_) {
    done = std::move(cur_);
    finish(*done);
  }
  cur_ = GnssFix{};
  cur_dropped_ = false;
  cur_datum_ok_ = datum_ok_;  // a DTM applies to the epochs that start after it
  cur_->time_of_day_s = tod;
  cur_->t_receive_s = receive_s;
  // the date: the last RMC's, moved on a day when the time of day wrapped past midnight
  if (std::isfinite(last_tod_) && tod < last_tod_ - 43200 && std::isfinite(date_epoch_s_)) date_epoch_s_ += 86400;
  last_tod_ = tod;
  if (std::isfinite(date_epoch_s_)) cur_->t_receiver_s = date_epoch_s_ + tod;
  if (!std::isfinite(receive_s)) cur_->t_receive_s = cur_->t_receiver_s;
  // time checks on the epoch's stamp
  const double t = std::isfinite(cur_->t_receiver_s) ? cur_->t_receiver_s : tod;
  if (std::isfinite(last_t_)) {
    if (t < last_t_) {
      ++c_.time_backwards;
      problem("time goes back " + std::to_string(last_t_ - t) + " s");
      cur_dropped_ = true;
    } else if (t - last_t_ > p_.max_gap_s) {
      ++c_.time_jumps;
      problem("time jumps " + std::to_string(t - last_t_) + " s");
    }
  }
  if (!cur_dropped_) last_t_ = t;
  return done;
}

std::optional<GnssFix> NmeaParser::feed(const std::string& raw, double receive_s) {
  ++c_.lines;
  std::string s = raw;
  while (!s.empty() && (s.back() == '\r' || s.back() == '\n' || s.back() == ' ')) s.pop_back();
  const size_t dollar = s.find('$');
  const size_t star = s.rfind('*');
  if (p_.checksum_optional && dollar != std::string::npos && (star == std::string::npos || star < dollar)) {
    ++c_.sentences;
    return sentence(s.substr(dollar + 1), receive_s);
  }
  if (dollar == std::string::npos || star == std::string::npos || star < dollar || star + 3 != s.size()) {
    ++c_.bad_checksum;
    problem("no checksum");
    return std::nullopt;
  }
  uint8_t sum = 0;
  for (size_t i = dollar + 1; i < star; ++i) sum ^= static_cast<uint8_t>(s[i]);
  char* end = nullptr;
  const long given = std::strtol(s.c_str() + star + 1, &end, 16);
  if (end != s.c_str() + s.size() || given != sum) {
    ++c_.bad_checksum;
    problem("bad checksum");
    return std::nullopt;
  }
  ++c_.sentences;
  return sentence(s.substr(dollar + 1, star - dollar - 1), receive_s);
}

std::optional<GnssFix> NmeaParser::sentence(const std::string& body, double receive_s) {
  const auto f = splitFields(body);
  if (f[0].size() < 5) {
    ++c_.malformed;
    problem("no sentence type");
    return std::nullopt;
  }
  const std::string type = f[0].substr(f[0].size() - 3);
  auto malformed = [&](const char* what) -> std::optional<GnssFix> {
    ++c_.malformed;
    problem(type + ": " + what);
    return std::nullopt;
  };
  double tod = 0;
  std::optional<GnssFix> done;
  if (type == "GGA") {
    if (f.size() < 12 || !timeOfDay(f[1], tod)) return malformed("time");
    done = startEpoch(tod, receive_s);
    if (cur_dropped_) return done;
    GnssFix& e = *cur_;
    const int q = std::atoi(f[6].c_str());
    e.quality = q;
    e.satellites = std::atoi(f[7].c_str());
    double v;
    if (toDouble(f[8], v)) e.hdop = v;
    if (q > 0) {
      double lat, lon, alt = 0, sep = 0;
      if (!angle(f[2], f[3], 2, lat) || !angle(f[4], f[5], 3, lon) || std::abs(lat) > 90) {
        e.quality = 0;
        ++c_.malformed;
        problem("GGA: position");
        return done;
      }
      toDouble(f[9], alt);
      toDouble(f[11], sep);
      e.position = {lat, lon, alt + sep};
      e.has_position = true;
    }
    appendType(e, type);
  } else if (type == "RMC") {
    if (f.size() < 10 || !timeOfDay(f[1], tod)) return malformed("time");
    double day;
    if (dateEpoch(f[9], day)) {
      date_epoch_s_ = day;
      last_tod_ = kNaN;  // the date is now known: no wrap to apply
    }
    done = startEpoch(tod, receive_s);
    if (cur_dropped_) return done;
    GnssFix& e = *cur_;
    if (std::isfinite(date_epoch_s_)) e.t_receiver_s = date_epoch_s_ + tod;
    e.rmc_status = f[2].empty() ? 'V' : f[2][0];
    double v;
    if (toDouble(f[7], v)) e.speed_mps = v * kKnot_mps;
    if (toDouble(f[8], v)) e.course_rad = v * kDeg;
    if (!e.has_position && (e.rmc_status == 'A' || p_.void_positions)) {
      double lat, lon;
      const bool read = angle(f[3], f[4], 2, lat) && angle(f[5], f[6], 3, lon) && std::abs(lat) <= 90;
      if (!read && e.rmc_status == 'A') {
        e.rmc_status = 'V';
        ++c_.malformed;
        problem("RMC: position");
        return done;
      }
      if (read) {
        e.position = {lat, lon, e.position.h_m};
        e.has_position = true;
      }
    }
    appendType(e, type);
  } else if (type == "GST") {
    if (f.size() < 9 || !timeOfDay(f[1], tod)) return malformed("time");
    done = startEpoch(tod, receive_s);
    if (cur_dropped_) return done;
    GnssFix& e = *cur_;
    double a, b, c;
    if (toDouble(f[6], a) && toDouble(f[7], b)) {
      e.sigma_lat_m = a;
      e.sigma_lon_m = b;
      if (toDouble(f[8], c)) e.sigma_alt_m = c;
    }
    appendType(e, type);
  } else if (type == "VTG") {
    if (!cur_ || cur_dropped_) return std::nullopt;  // no epoch to attach it to
    double v;
    if (f.size() > 1 && toDouble(f[1], v)) cur_->course_rad = v * kDeg;
    if (f.size() > 7 && toDouble(f[7], v)) cur_->speed_mps = v / 3.6;
    else if (f.size() > 5 && toDouble(f[5], v)) cur_->speed_mps = v * kKnot_mps;
    appendType(*cur_, type);
  } else if (type == "DTM") {
    if (f.size() < 2) return malformed("datum");
    const bool ok = f[1] == "W84" && (f.size() < 9 || f[8].empty() || f[8] == "W84");
    if (!ok && datum_ok_) problem("datum " + f[1] + " (not WGS84): its fixes are dropped");
    datum_ok_ = ok;
  } else {
    ++c_.unsupported;
  }
  if (done) c_.fixes += done->valid() && done->has_position;
  return done;
}

std::optional<GnssFix> NmeaParser::flush() {
  if (!cur_) return std::nullopt;
  std::optional<GnssFix> done = std::move(cur_);
  cur_.reset();
  finish(*done);
  c_.fixes += done->valid() && done->has_position;
  return done;
}

std::optional<GnssFix> parseRmc(const std::string& sentence) noexcept {
  try {
    if (sentence.size() < 7 || sentence[0] != '$' || sentence.compare(3, 3, "RMC") != 0) return std::nullopt;
    NmeaParams p;
    p.checksum_optional = true;
    p.void_positions = true;
    NmeaParser parser(p);
    parser.feed(sentence);
    std::optional<GnssFix> f = parser.flush();
    const NmeaCounters& c = parser.counters();
    if (!f || c.sentences != 1 || c.malformed != 0 || !f->has_position) return std::nullopt;
    if (f->rmc_status != 'A' && f->rmc_status != 'V') return std::nullopt;
    return f;
  } catch (...) {
    return std::nullopt;  // allocation failure only
  }
}

NmeaLog parseNmeaLog(const std::string& text, NmeaParams p) {
  NmeaParser parser(p);
  NmeaLog log;
  std::istringstream in(text);
  std::string line;
  auto take = [&](std::optional<GnssFix> f) {
    if (f && f->valid() && f->has_position) log.fixes.push_back(std::move(*f));
  };
  while (std::getline(in, line)) {
    if (line.empty() || line == "\r") continue;
    double receive = kNaN;
    if (line[0] != '$') {
      char* end = nullptr;
      const double v = std::strtod(line.c_str(), &end);
      if (end != line.c_str() && *end == ' ') {
        receive = v;
        line = line.substr(static_cast<size_t>(end - line.c_str()) + 1);
      }
    }
    take(parser.feed(line, receive));
  }
  take(parser.flush());
  log.counters = parser.counters();
  log.problems = parser.problems();
  return log;
}

NmeaLog readNmeaLog(const std::string& path, NmeaParams p) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open NMEA log '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return parseNmeaLog(ss.str(), p);
}

std::string nmeaSentence(const std::string& body) {
  uint8_t sum = 0;
  for (char c : body) sum ^= static_cast<uint8_t>(c);
  char tail[8];
  std::snprintf(tail, sizeof(tail), "*%02X", sum);
  return "$" + body + tail;
}

std::string encodeGga(const GnssFix& f, const std::string& talker) {
  char b[200];
  const int q = f.quality < 0 ? (f.valid() ? 1 : 0) : f.quality;
  if (q > 0 && f.has_position) {
    std::snprintf(b, sizeof(b), "%sGGA,%s,%s,%s,%d,%02d,%.1f,%.4f,M,0.0,M,,", talker.c_str(),
                  hhmmss(f.time_of_day_s).c_str(), latLon(f.position.lat_deg, 2, 'N', 'S').c_str(),
                  latLon(f.position.lon_deg, 3, 'E', 'W').c_str(), q, f.satellites,
                  std::isfinite(f.hdop) ? f.hdop : 99.9, f.position.h_m);
  } else {
    std::snprintf(b, sizeof(b), "%sGGA,%s,,,,,0,%02d,99.9,,M,,M,,", talker.c_str(), hhmmss(f.time_of_day_s).c_str(),
                  f.satellites);
  }
  return nmeaSentence(b);
}

std::string encodeRmc(const GnssFix& f, const std::string& talker) {
  const auto secs = static_cast<std::time_t>(std::floor(f.t_receiver_s));
  std::tm tm{};
  gmtime_r(&secs, &tm);
  const bool ok = f.valid();
  const double course = std::isfinite(f.course_rad) ? std::fmod(f.course_rad / kDeg + 360.0, 360.0) : 0.0;
  const double knots = std::isfinite(f.speed_mps) ? f.speed_mps / kKnot_mps : 0.0;
  char b[200];
  if (ok) {
    std::snprintf(b, sizeof(b), "%sRMC,%s,A,%s,%s,%.3f,%.2f,%02d%02d%02d,,,A", talker.c_str(),
                  hhmmss(f.time_of_day_s).c_str(), latLon(f.position.lat_deg, 2, 'N', 'S').c_str(),
                  latLon(f.position.lon_deg, 3, 'E', 'W').c_str(), knots, course, tm.tm_mday, tm.tm_mon + 1,
                  tm.tm_year % 100);
  } else {
    std::snprintf(b, sizeof(b), "%sRMC,%s,V,,,,,,,%02d%02d%02d,,,N", talker.c_str(), hhmmss(f.time_of_day_s).c_str(),
                  tm.tm_mday, tm.tm_mon + 1, tm.tm_year % 100);
  }
  return nmeaSentence(b);
}

std::string encodeVtg(const GnssFix& f, const std::string& talker) {
  const double course = std::isfinite(f.course_rad) ? std::fmod(f.course_rad / kDeg + 360.0, 360.0) : 0.0;
  const double v = std::isfinite(f.speed_mps) ? f.speed_mps : 0.0;
  char b[120];
  std::snprintf(b, sizeof(b), "%sVTG,%.2f,T,,M,%.3f,N,%.3f,K,A", talker.c_str(), course, v / kKnot_mps, v * 3.6);
  return nmeaSentence(b);
}

std::string encodeGst(const GnssFix& f, const std::string& talker) {
  const double rms = std::sqrt(0.5 * (f.sigma_lat_m * f.sigma_lat_m + f.sigma_lon_m * f.sigma_lon_m));
  char b[160];
  std::snprintf(b, sizeof(b), "%sGST,%s,%.3f,%.3f,%.3f,0.0,%.3f,%.3f,%.3f", talker.c_str(),
                hhmmss(f.time_of_day_s).c_str(), rms, std::max(f.sigma_lat_m, f.sigma_lon_m),
                std::min(f.sigma_lat_m, f.sigma_lon_m), f.sigma_lat_m, f.sigma_lon_m, f.sigma_alt_m);
  return nmeaSentence(b);
}

}  // namespace roadslam::gnss

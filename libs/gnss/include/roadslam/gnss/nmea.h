#pragma once
/// \file nmea.h
/// NMEA 0183 GNSS sentences: the parser (GGA, RMC, VTG, GST, DTM; any talker: GP, GN, GL, GA, ...)
/// that groups the sentences of one receiver epoch into a GnssFix, and the encoder the simulator and
/// the tests write with. The parser never throws on a sentence: every problem is counted and named.
///
/// Sentence format (NMEA 0183 v4.10): `$ttSSS,f1,f2,...*HH` with HH the hex XOR of the characters
/// between '$' and '*'. Examples:
///   $GPGGA,123519.00,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47   time, lat ddmm.mmmm, lon
///        dddmm.mmmm, quality (0 = no fix), satellites, HDOP, altitude MSL [m], geoid separation [m]
///   $GPRMC,123519.00,A,4807.038,N,01131.000,E,022.4,084.4,230394,003.1,W*6A  status A/V, knots, course, date
///   $GPVTG,084.4,T,,M,022.4,N,041.5,K,A*hh     course over ground (true), speed knots / km/h
///   $GPGST,123519.00,1.2,1.5,0.9,30.0,1.1,0.8,2.0*hh  rms, error ellipse (major, minor, orientation),
///        1-sigma latitude, longitude, altitude errors [m]
///   $GPDTM,W84,,0.0,N,0.0,E,0.0,W84*hh          local datum (W84 = WGS84; anything else is counted)
///
/// Log file format (`readNmeaLog`, written by the simulator and by `roadslam-grab`): one sentence per
/// line, optionally preceded by the host receive time and a space: `1700000000.123456 $GPGGA,...`.
/// Lines without a receive time take the receiver's own time as their receive time.

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "roadslam/gnss/geo.h"

namespace roadslam::gnss {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One receiver epoch: the sentences sharing one UTC time of day. The one GNSS fix type: a receiver's
/// NMEA epoch, the RMC a Velodyne forwards in its position packets, a rawlog's CObservationGPS record,
/// a u-blox CSV row.
struct GnssFix {
  double time_of_day_s = kNaN;  ///< receiver UTC time of day [s]
  double t_receiver_s = kNaN;   ///< receiver UTC time [s since the Unix epoch]; NaN before the first RMC date
  double t_receive_s = kNaN;    ///< host receive time of the epoch's first sentence [s since epoch]
  bool has_position = false;    ///< a GGA or RMC position was read
  Geodetic position;            ///< WGS84; h = GGA altitude + geoid separation (ellipsoidal) [deg, m]
  int quality = -1;             ///< GGA fix quality (0 none, 1 GPS, 2 DGPS, 4 RTK fixed, 5 float); -1 no GGA
  int satellites = 0;           ///< GGA satellites in use [-]
  double hdop = kNaN;           ///< GGA horizontal dilution of precision [-]
  char rmc_status = 0;          ///< RMC 'A' valid / 'V' void; 0 without RMC
  double speed_mps = kNaN;      ///< speed over ground (RMC or VTG) [m/s]
  double course_rad = kNaN;     ///< course over ground, clockwise from true north [rad]
  double sigma_lat_m = kNaN, sigma_lon_m = kNaN, sigma_alt_m = kNaN;  ///< GST 1-sigma errors [m]
  std::string sentences;        ///< types read, e.g. "GGA,RMC,GST"
  /// The sensor it came from where the input holds several: a CObservationGPS record's sensorLabel
  /// (roadslam-grab's `<lidar>_GPS`, a receiver's `[gnss] label`, `CAN_GPS`), or the position packets
  /// of a capture (sources::kPositionPacketsLabel); empty when the input has one source.
  std::string label;

  /// A position the receiver calls a fix (GGA quality > 0, or RMC 'A' without GGA).
  bool valid() const;
  /// The time to use: the receiver's when known, else the receive time [s since epoch].
  double stamp(bool prefer_receiver = true) const;
  /// Position covariance in ENU [m^2]: from GST's sigmas, else HDOP x \p uere_m horizontally and
  /// 2 HDOP x uere vertically, else \p fallback_sigma_m on every axis.
  Eigen::Matrix3d covarianceEnu(double uere_m, double fallback_sigma_m) const;
};

/// What the parser met, by name. Every count is also in named().
struct NmeaCounters {
  uint64_t lines = 0;          ///< lines fed
  uint64_t sentences = 0;      ///< sentences with a good checksum
  uint64_t epochs = 0;         ///< epochs completed
  uint64_t fixes = 0;          ///< epochs with a valid position
  uint64_t bad_checksum = 0;   ///< missing or wrong *HH
  uint64_t malformed = 0;      ///< good checksum, unreadable field
  uint64_t no_fix = 0;         ///< epochs with GGA quality 0 / RMC 'V' / no position
  uint64_t time_backwards = 0; ///< epochs older than the previous one (dropped)
  uint64_t time_jumps = 0;     ///< epochs more than NmeaParams::max_gap_s after the previous one (kept)
  uint64_t other_datum = 0;    ///< epochs in a datum other than WGS84 (DTM), dropped
  uint64_t unsupported = 0;    ///< well-formed sentences of other types (GSA, GSV, ...), ignored
  std::map<std::string, uint64_t> named() const;
};

struct NmeaParams {
  double max_gap_s = 2.0;  ///< a step between epochs above this counts as a time jump [s]
  /// Sentences without `*HH` are read (NMEA 0183 made the checksum mandatory only in v2.3; older
  /// devices, and some Velodyne firmware forwarding them, omit it); else counted as bad_checksum.
  bool checksum_optional = false;
  /// A void RMC ('V') keeps the position it carries (has_position; valid() stays false).
  bool void_positions = false;
};

class NmeaParser {
 public:
  explicit NmeaParser(NmeaParams p = {}) : p_(p) {}
  /// Feeds one line (CR/LF tolerated) received at \p receive_s [s since epoch, NaN = unknown].
  /// Returns the previous epoch when this sentence starts a new one (valid or not: see valid()).
  std::optional<GnssFix> feed(const std::string& line, double receive_s = kNaN);
  /// The epoch being assembled, if any (call at the end of the input).
  std::optional<GnssFix> flush();
  const NmeaCounters& counters() const { return c_; }
  /// The first problems met, each "line N: what" (at most 20).
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  void problem(const std::string& what);
  std::optional<GnssFix> sentence(const std::string& body, double receive_s);  ///< body: between $ and *
  std::optional<GnssFix> startEpoch(double tod, double receive_s);
  void finish(GnssFix& f);
  NmeaParams p_;
  NmeaCounters c_;
  std::vector<std::string> problems_;
  std::optional<GnssFix> cur_;
  double date_epoch_s_ = kNaN;  ///< midnight UTC of the last RMC date [s since epoch]
  double last_tod_ = kNaN;      ///< time of day of the last completed epoch [s]
  double last_t_ = kNaN;        ///< stamp of the last accepted epoch [s]
  bool datum_ok_ = true;        ///< the last DTM named WGS84 (or none was seen)
  bool cur_dropped_ = false;
  bool cur_datum_ok_ = true;    ///< datum_ok_ when the epoch being assembled started    ///< the epoch being assembled went back in time
};

/// One RMC sentence alone, as a Velodyne forwards its receiver's in a position packet (VLP-16 manual
/// 9.4): checksum optional, a void fix keeps its position. nullopt unless it is an RMC with status A
/// or V and a readable time and position. Never throws.
std::optional<GnssFix> parseRmc(const std::string& sentence) noexcept;

/// The valid fixes of an NMEA log file (format above), in order, and what was dropped.
struct NmeaLog {
  std::vector<GnssFix> fixes;
  NmeaCounters counters;
  std::vector<std::string> problems;
};
/// Reads \p path; throws std::runtime_error naming the file when it cannot be opened. Bad lines are
/// counted, never fatal.
NmeaLog readNmeaLog(const std::string& path, NmeaParams p = {});
/// Parses a log held in memory (same format).
NmeaLog parseNmeaLog(const std::string& text, NmeaParams p = {});

// ---- encoder ----
/// `$` + body + `*HH` (no CR/LF).
std::string nmeaSentence(const std::string& body);
/// GGA of \p f (time of day, position, quality, satellites, HDOP; altitude = h, separation 0).
std::string encodeGga(const GnssFix& f, const std::string& talker = "GP");
/// RMC of \p f (needs t_receiver_s for the date).
std::string encodeRmc(const GnssFix& f, const std::string& talker = "GP");
/// VTG of \p f (course, speed).
std::string encodeVtg(const GnssFix& f, const std::string& talker = "GP");
/// GST of \p f (sigma_lat_m, sigma_lon_m, sigma_alt_m; rms = their horizontal rms).
std::string encodeGst(const GnssFix& f, const std::string& talker = "GP");

}  // namespace roadslam::gnss

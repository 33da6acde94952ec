#pragma once
/// \file nmea_source.h
/// GNSS receivers that speak NMEA 0183, behind one interface with two live backends and a replay
/// backend: a serial port (termios, raw 8N1), a gpsd daemon (libgps, Debian `libgps-dev`:
/// gpsd passes the receiver's sentences through in NMEA watch mode), and an NMEA log
/// (libs/gnss/nmea.h format) replayed with its recorded receive times. Each line comes with its host
/// receive time (CLOCK_REALTIME when the line's end was read; through gpsd, when gpsd's copy was
/// read, a few ms after the receiver sent it). recordNmea() writes what it reads in the log format,
/// which the replay backend, `roadslam-map --gnss` and `roadslam-rawlog nmea` read: the recording
/// format is the replay format.

#include <memory>
#include <string>
#include <vector>

namespace roadslam::sources {

/// One NMEA sentence as received.
struct NmeaLine {
  double receive_s = 0;  ///< host receive time [s since epoch]
  std::string text;      ///< the sentence, without CR/LF
};

enum class NmeaRead { Line, Timeout, End };

class NmeaSource {
 public:
  virtual ~NmeaSource() = default;
  /// Waits up to \p timeout_ms for the next line. Never throws after construction: a read error
  /// ends the source (End) with errorMessage() set.
  virtual NmeaRead read(NmeaLine& out, int timeout_ms) = 0;
  virtual std::string describe() const = 0;
  virtual std::string errorMessage() const { return {}; }
};

/// A serial device (e.g. /dev/ttyUSB0, or a pty in tests) at \p baud (4800 ... 921600), raw 8N1.
/// Throws std::runtime_error naming the device when it cannot be opened or configured.
class SerialNmeaSource : public NmeaSource {
 public:
  SerialNmeaSource(const std::string& device, int baud);
  ~SerialNmeaSource() override;
  SerialNmeaSource(const SerialNmeaSource&) = delete;
  SerialNmeaSource& operator=(const SerialNmeaSource&) = delete;
  NmeaRead read(NmeaLine& out, int timeout_ms) override;
  std::string describe() const override { return "serial:" + device_; }
  std::string errorMessage() const override { return error_; }

 private:
  std::string device_, buffer_, error_;
  int fd_ = -1;
  std::size_t max_line_ = 512;  ///< a longer line without LF is noise: dropped
};

/// A gpsd client (gpsd's JSON protocol, `?WATCH={"enable":true,"nmea":true}` through libgps): the
/// NMEA sentences gpsd relays from its receivers (of \p device only, when not empty). gpsd's own
/// JSON reports are skipped and counted (jsonLines()). Throws naming host:port when gpsd cannot be
/// reached; a lost connection ends the source (End, errorMessage()).
class GpsdNmeaSource : public NmeaSource {
 public:
  GpsdNmeaSource(const std::string& host, int port, const std::string& device = "");
  ~GpsdNmeaSource() override;
  GpsdNmeaSource(const GpsdNmeaSource&) = delete;
  GpsdNmeaSource& operator=(const GpsdNmeaSource&) = delete;
  NmeaRead read(NmeaLine& out, int timeout_ms) override;
  std::string describe() const override { return "gpsd:" + where_; }
  std::string errorMessage() const override { return error_; }
  std::size_t jsonLines() const { return json_lines_; }

 private:
  struct Impl;  // libgps's gps_data_t stays in gpsd_source.cpp
  std::unique_ptr<Impl> impl_;
  std::string where_, error_;
  std::size_t json_lines_ = 0;
};

/// An NMEA log replayed: lines with a receive time keep it; lines without one take the time of the
/// line before (or 0). \p speed > 0 paces the lines at that multiple of their recorded spacing,
/// 0 returns them at once. Throws naming the file when it cannot be read.
class NmeaLogReplaySource : public NmeaSource {
 public:
  explicit NmeaLogReplaySource(const std::string& path, double speed = 0);
  NmeaRead read(NmeaLine& out, int timeout_ms) override;
  std::string describe() const override { return "nmea-log:" + path_; }

 private:
  std::string path_;
  double speed_;
  std::vector<NmeaLine> lines_;
  std::size_t next_ = 0;
  double wall0_ = -1, t0_ = 0;
};

struct NmeaRecordSummary {
  std::size_t lines = 0;   ///< lines written to the log
  std::size_t epochs = 0;  ///< CObservationGPS written to the rawlog (valid fixes)
  std::string error;       ///< the source's error when it ended on one
};

/// Reads \p src until it ends, \p max_lines lines (0 = no limit) or stopRequested() (common/stop_signal.h),
/// writing every line to \p log_path (log format) and each valid epoch to \p rawlog_path (empty = none)
/// as CObservationGPS labelled \p label. Both files are written atomically.
NmeaRecordSummary recordNmea(NmeaSource& src, const std::string& log_path, const std::string& rawlog_path,
                             std::size_t max_lines = 0, const std::string& label = "GPS");

}  // namespace roadslam::sources

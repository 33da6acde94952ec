#pragma once
/// \file params.h
/// Configuration of a recording session, loaded from one ini (ini/grab.ini):
///
///     [grab]            sensors = front,rear   ; section names of the LiDARs (comma separated)
///                       can = can              ; section of the CAN source, empty = no CAN
///                       gnss = gnss            ; section of the GNSS receiver, empty = none
///                       queue_capacity, rotate_size_mb, rotate_period_s, flush_period_ms, ...
///     [front]           data_port, position_port, bind_address, source_filter, ... (UdpReceiver)
///                       sensor_label, model, calibration_file, x_m.., yaw_deg.. (RawlogWriter keys)
///     [can]             source = socketcan|candump|none, interface, candump_file, vehicle_ini ...
///     [gnss]            source = serial|gpsd|nmea_log|none, device, baud, gpsd_host, nmea_file ...
///
/// Units: SI inside; ini keys with a unit suffix (_ms, _mb) are converted on load.

#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/can/socketcan_source.h"
#include "roadslam/rawlog/rawlog_writer.h"
#include "roadslam/sources/udp_receiver.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::grabber {

/// One LiDAR: where it listens and how its sweeps are labelled and mounted.
struct SensorParams {
  std::string section;                  ///< ini section name (also the sidecar file stem)
  sources::UdpReceiver::Params udp;     ///< ports, bind address, sender filter, socket buffer
  rawlog::RawlogWriter::Params scan;   ///< sensorLabel, model, calibration, T_base_lidar, ranges
  double silent_after_s = 1.0;          ///< watchdog: no packet for this long = silent [s]
  /// Without source_filter: record only the first sender seen on the ports; packets of any other
  /// sender (a second sensor on the same port) are counted as foreign and not recorded.
  bool lock_first_sender = true;

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Reads the UdpReceiver keys, the RawlogWriter keys and silent_after_ms (-> s).
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const;
};

/// The CAN bus: live SocketCAN, a candump log replayed (tests, re-recording), or none.
struct CanParams {
  enum class Source { None, SocketCan, Candump };
  Source source = Source::None;
  can::SocketCanParams socketcan;   ///< interface, filters, error frames ...
  std::string candump_file;         ///< log replayed when source = candump
  bool candump_realtime = true;     ///< replay at the recorded pace (else as fast as possible)
  bool restamp = true;              ///< replayed frames get the host receive time (one clock)
  std::string vehicle_ini;          ///< ini/vehicles/<car>.ini: decode into MRPT observations; empty = none
  std::string data_root;            ///< root for the vehicle ini's DBC path; empty = the ini's own
  double silent_after_s = 1.0;      ///< watchdog: no frame for this long = bus silent [s] (ini: silent_after_ms)

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Keys: source (none|socketcan|candump), the SocketCanParams keys, candump_file,
  /// candump_realtime, restamp, vehicle_ini, data_root.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& sec) const;
};

/// An NMEA 0183 GNSS receiver (sources/nmea_source.h): a serial port, a gpsd daemon, an NMEA log
/// replayed (tests, re-recording), or none.
struct GnssParams {
  enum class Source { None, Serial, Gpsd, NmeaLog };
  Source source = Source::None;
  std::string device = "/dev/ttyACM0";  ///< serial device
  int baud = 9600;                      ///< serial speed [bit/s]
  std::string gpsd_host = "localhost";
  int gpsd_port = 2947;                 ///< gpsd's TCP port
  std::string gpsd_device;              ///< only this receiver of gpsd's (its path), empty = all
  std::string nmea_file;                ///< log replayed when source = nmea_log
  double replay_speed = 1.0;            ///< replay pace: multiple of the recorded spacing, 0 = at once [-]
  bool restamp = true;                  ///< replayed lines get the host receive time (one clock)
  std::string label = "GNSS";           ///< sensorLabel of the CObservationGPS
  /// An epoch (the sentences sharing one UTC time) is complete when the next one starts or when no
  /// sentence came for this long: receivers send an epoch as one burst [s] (ini: epoch_idle_ms).
  double epoch_idle_s = 0.1;
  double max_gap_s = 2.0;               ///< epochs further apart count as a time jump [s] (ini: max_gap_ms)
  double silent_after_s = 3.0;          ///< watchdog: no sentence for this long = silent [s] (ini: silent_after_ms)

  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& sec) const;
};

/// Queues, file rotation and the writer's clock.
struct WriterParams {
  std::size_t queue_capacity = 512;   ///< per-source queue: sweeps / position packets / CAN frames [items]
  std::size_t can_queue_capacity = 65536;  ///< CAN queue [frames]
  double rotate_size_bytes = 512e6;   ///< start a new rawlog segment past this size [bytes] (ini: rotate_size_mb)
  double rotate_period_s = 0;         ///< and/or after this long [s]; 0 = no time rotation
  double flush_period_s = 0.5;        ///< gzip Z_SYNC_FLUSH + sidecar flush period [s] (ini: flush_period_ms)
  double reorder_window_s = 0.3;      ///< observations are held this long to be written in time order [s]
  int compression_level = 1;          ///< gzip level 0..9 [-]
  bool pcap_sidecar = true;           ///< also write <sensor>.pcap (every packet, lossless)
  bool candump_sidecar = true;        ///< also write can.candump.log
  bool nmea_sidecar = true;           ///< also write gnss.nmea.log (every line, its receive time)
  double status_period_s = 1.0;       ///< status line / summary.json refresh [s]
  std::string file_prefix = "grab";   ///< segments are <prefix>_000.rawlog, _001 ...

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& sec);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& sec) const;
};

struct GrabParams {
  std::vector<SensorParams> sensors;
  CanParams can;
  GnssParams gnss;
  WriterParams writer;

  /// Loads [grab] and the sections it names; throws naming the file/section/key on a bad value,
  /// an unknown key, or two sensors on the same data port.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg) const;
  static GrabParams fromFile(const std::string& path);
};

}  // namespace roadslam::grabber

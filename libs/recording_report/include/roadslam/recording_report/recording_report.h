#pragma once
/// \file recording_report.h
/// The recording report of a drive (`roadslam-report`): per sensor the first/last stamp,
/// count, mean rate, gaps and drops and the rate over time; the CAN log's frame rates per id, its
/// decoded signals and the dead-reckoned path; optionally a `roadslam-map` folder's trajectory and
/// pictures. Written as one self-contained report.html and the same figures as report.json.
/// Times are seconds since the Unix epoch unless a name says "since start" (the earliest stamp of
/// any stream of the recording). Everything in SI units.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace roadslam::recording_report {

struct ReportParams {
  double gap_factor = 3.0;              ///< an interval over gap_factor x the nominal period is a gap [-]
  double min_gap_s = 0.05;              ///< shorter intervals are never gaps [s]
  double rate_bin_s = 1.0;              ///< bin of the rate-over-time plots [s]
  std::size_t max_rate_bins = 2000;     ///< more bins than this widen rate_bin_s [count]
  std::size_t max_listed_gaps = 20;     ///< gaps listed per stream, the longest; all are counted [count]
  std::size_t max_plot_points = 3000;   ///< points per plotted series, decimated beyond [count]
  std::size_t max_listed_issues = 10;   ///< bad CAN log lines listed with their line numbers [count]
};

/// An interval between two consecutive messages of a stream longer than the gap threshold.
struct Gap {
  double start_s = 0;  ///< stamp of the message before the gap [s since epoch]
  double end_s = 0;    ///< stamp of the message after it [s since epoch]
  double length() const { return end_s - start_s; }
};

/// One stream of timed messages: a LiDAR's data packets, its position packets, GPS records, a CAN bus.
struct StreamStats {
  std::string label;               ///< e.g. "velodyne 192.168.1.201:2368", "gps", "can0"
  std::string kind;                ///< lidar | gps | can | rawlog (other records, e.g. the grabber's CAN observations)
  std::uint64_t count = 0;         ///< messages [count]
  double first_s = 0, last_s = 0;  ///< [s since epoch]
  double rate_hz = 0;              ///< (count - 1) / (last - first) [Hz]
  double nominal_period_s = 0;     ///< the sensor's period (Velodyne packet clock) or the median interval [s]
  double gap_threshold_s = 0;      ///< max(gap_factor x nominal, min_gap_s) [s]
  std::uint64_t gap_count = 0;     ///< intervals over the threshold [count]
  double gap_time_s = 0;           ///< their summed length [s]
  std::vector<Gap> gaps;           ///< the longest max_listed_gaps, in time order
  std::uint64_t drops = 0;         ///< messages missing per the sensor's own clock (Velodyne) [count]
  std::uint64_t malformed = 0;     ///< wrong-size / undecodable messages [count]
  std::string model;               ///< lidar: vlp16, hdl32: as decoded (velodyne/model_choice.h)
  std::string model_source;        ///< lidar: why: ini (--lidar-model), packet layout, product byte
  std::uint64_t sweeps = 0;        ///< lidar: complete turns seen (wrap to wrap, none spanning lost packets) [count]
  double sweep_rate_hz = 0;        ///< lidar: rotation rate, sweeps / their summed duration [Hz]
  std::vector<double> bin_t_s;     ///< rate over time: bin start [s since start]
  std::vector<double> bin_rate_hz; ///< messages in the bin / bin width [Hz]
};

/// Frames of one CAN id.
struct CanIdStats {
  std::string iface;
  std::uint32_t id = 0;
  bool extended = false;
  std::string name;                ///< DBC message name ("" when no DBC or not in it)
  std::uint64_t count = 0;         ///< [count]
  double rate_hz = 0;              ///< [Hz]
  double median_period_s = 0;      ///< [s]
  double max_period_s = 0;         ///< [s]
  std::uint64_t gaps = 0;          ///< intervals over gap_factor x the median [count]
};

/// A decoded signal over time (decimated for plotting).
struct SignalSeries {
  std::string name;                ///< speed, yaw_rate, steering_angle
  std::string unit;                ///< m/s, rad/s, rad
  std::vector<double> t_s;         ///< [s since start]
  std::vector<double> value;       ///< [unit]
  double min = 0, max = 0, mean = 0;
};

struct CanReport {
  std::string log;                             ///< candump log path(s), comma-separated
  std::uint64_t lines = 0, frames = 0, bad_lines = 0;
  std::vector<std::string> issues;             ///< "LOG:LINE: reason" of the first bad lines
  std::vector<CanIdStats> ids;                 ///< sorted by interface then id
  std::string vehicle;                         ///< car name from the vehicle ini ("" without one)
  std::vector<SignalSeries> signals;           ///< with a vehicle ini
  std::vector<double> path_x_m, path_y_m;      ///< dead-reckoned T_odom_base, decimated [m]
  double path_length_m = 0;                    ///< integrated distance [m]
  double dead_reckoning_gap_time_s = 0;        ///< time not integrated (speed updates too far apart) [s]
};

struct MapReport {
  std::string dir;
  std::vector<double> x_m, y_m;                ///< trajectory.tum T_map_lidar translation, decimated [m]
  std::uint64_t poses = 0;                     ///< [count]
  double length_m = 0;                         ///< trajectory length [m]
  std::vector<std::string> pictures;           ///< map_top.png, grid.png when present (full paths)
  nlohmann::json summary;                      ///< the map's summary.json figures (frames, loops...)
};

struct RecordingReport {
  std::string recording;                       ///< path given
  std::vector<std::string> files;              ///< files read (a grab folder's segments in order)
  std::string format;                          ///< pcap | rawlog
  std::string damage;                          ///< "" or the place the recording is damaged (file, record, byte)
  double start_s = 0, end_s = 0;               ///< earliest / latest stamp of any stream [s since epoch]
  std::vector<std::string> warnings;           ///< e.g. a CAN log that does not overlap the recording in time
  std::uint64_t sensor_records = 0;            ///< rawlog records that are neither Velodyne nor GPS [count]
  std::vector<StreamStats> streams;
  /// Valid GNSS fixes (position packets' or rawlog's RMC) in a local east-north plane about the first
  /// one (equirectangular, fine over a few km), decimated [m]; their times [s since start].
  std::vector<double> gnss_t_s, gnss_x_m, gnss_y_m;
  std::uint64_t gnss_fixes = 0;                ///< valid fixes [count]
  double gnss_length_m = 0;                    ///< fix-to-fix path length [m]
  std::optional<CanReport> can;
  std::optional<MapReport> map;
};

struct ReportInputs {
  std::string recording;     ///< .pcap, .rawlog(.gz), or a roadslam-grab session folder
  std::string can_log;       ///< candump log; "" = a grab folder's can_*.candump.log sidecars, if any
  std::string vehicle_ini;   ///< ini/vehicles/X.ini: DBC names, decoded signals, dead reckoning
  std::string map_dir;       ///< roadslam-map output folder
  /// "" = the packets' product byte; vlp16 / hdl32 forced for captures whose byte lies (early VLP-16
  /// firmware reports the HDL-32E code): sets the packet period of the gap and drop counts.
  std::string lidar_model;
};

/// Reads everything. Throws std::runtime_error naming the file when an input is missing, unreadable or
/// holds no usable data; a recording damaged part way is reported up to the damage (RecordingReport::damage).
RecordingReport buildReport(const ReportInputs& in, const ReportParams& params = {});

/// Statistics of one stream from its stamps (any order is sorted) and, when > 0, its nominal period [s];
/// the bins start at \p start_s.
StreamStats streamStats(std::vector<double> stamps_s, double nominal_period_s, double start_s,
                        const ReportParams& params);

nlohmann::json toJson(const RecordingReport& r);
std::string toHtml(const RecordingReport& r);
/// Writes DIR/report.html and DIR/report.json (atomically), creating DIR.
void writeReport(const RecordingReport& r, const std::string& dir);

/// Why \p dir may not take the report of \p in (runfolder/output_folder.h: it must be new or empty,
/// or an earlier report of the same recording); empty when it may. Checked before the report is built.
std::string reportFolderRefusal(const std::string& dir, const ReportInputs& in);
/// Claims \p dir (run.json "writing"; \p force: whatever is there) once the report is built;
/// returns the warnings of a forced claim. writeReport marks it complete.
std::vector<std::string> claimReportFolder(const std::string& dir, const ReportInputs& in, bool force);
/// A few lines for the terminal.
std::string toText(const RecordingReport& r);

}  // namespace roadslam::recording_report

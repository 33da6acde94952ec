#pragma once
// Shared between the report's source files (not installed).
#include <string>
#include <vector>

#include "roadslam/recording_report/recording_report.h"

namespace roadslam::recording_report {

/// A stream's stamps, before streamStats(): the fields set here (label, kind, drops, sweeps...) are kept.
struct PendingStream {
  StreamStats info;
  std::vector<double> stamps;  ///< [s since epoch]
  double nominal_period_s = 0;  ///< 0 = the median interval [s]
};

/// The files of a recording: itself, or a grab folder's rawlog segments in order.
std::vector<std::string> recordingFiles(const std::string& path);
/// Reads r.files into streams; sets r.format, r.damage, r.sensor_records.
std::vector<PendingStream> readSensors(RecordingReport& r, const std::string& lidar_model);
/// A grab folder's CAN sidecars (can_*.candump.log), in order; empty for a file.
std::vector<std::string> canSidecars(const std::string& path);
/// Reads the CAN log(s); the bus's frames become one stream per interface.
CanReport readCan(const std::vector<std::string>& logs, const std::string& vehicle_ini, const ReportParams& p,
                  std::vector<PendingStream>& streams);
/// Shifts the CAN report's times to seconds since \p start_s.
void shiftCanTimes(CanReport& c, double start_s);
MapReport readMap(const std::string& dir, const ReportParams& p);
/// Every k-th element so that at most \p n remain (and the last one).
std::vector<double> decimate(const std::vector<double>& v, std::size_t n);

}  // namespace roadslam::recording_report

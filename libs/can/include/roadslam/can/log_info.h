#pragma once
/// \file log_info.h
/// Summary of a CAN recording: per id count, rate, timing gaps and lengths; against a DBC also
/// unknown ids and DLC mismatches. Used by `roadslam-can info`.

#include <roadslam/can/dbc.h>
#include <roadslam/can/frame.h>

#include <cstdint>
#include <string>
#include <vector>

namespace roadslam::can {

/// A hole in the timing of one id: an interval much longer than its median period.
struct TimingGap {
  std::string iface;
  std::uint32_t id = 0;
  bool extended = false;
  double t_s = 0;         ///< time of the frame after the gap [s since epoch]
  double length_s = 0;    ///< interval [s]
  double expected_s = 0;  ///< median interval of this id [s]
};

struct IdInfo {
  std::string iface;
  std::uint32_t id = 0;
  bool extended = false;
  std::size_t count = 0;
  double first_s = 0, last_s = 0;  ///< [s since epoch]
  double rate_hz = 0;              ///< (count - 1) / (last - first) [Hz]
  double median_period_s = 0;      ///< [s]
  double max_period_s = 0;         ///< [s]
  std::size_t gaps = 0;            ///< intervals > gap_factor * median
  std::uint8_t min_len = 255, max_len = 0;  ///< payload lengths seen [bytes]
  bool in_dbc = false;             ///< message defined in the DBC (when one was given)
  std::string name;                ///< DBC message name
  std::size_t dlc_mismatches = 0;  ///< frames whose length differs from the DBC size
};

struct LogInfo {
  std::size_t frames = 0;
  std::size_t error_frames = 0, remote_frames = 0, fd_frames = 0;
  double first_s = 0, last_s = 0;  ///< [s since epoch]
  bool non_monotonic = false;      ///< timestamps go backwards somewhere
  bool with_dbc = false;
  std::vector<IdInfo> ids;         ///< sorted by interface then id
  std::size_t unknown_ids = 0, unknown_frames = 0, dlc_mismatch_frames = 0;
  std::vector<TimingGap> gaps;     ///< the largest gaps first, at most max_gaps
};

/// \param gap_factor interval / median period above which an interval is a gap [-]
/// \param min_gap_s  shorter intervals are never gaps [s]
LogInfo analyzeLog(const std::vector<CanFrame>& frames, const Database* db = nullptr, double gap_factor = 3.0,
                   double min_gap_s = 0.05, std::size_t max_gaps = 20);

std::string formatLogInfoText(const LogInfo& info);
std::string formatLogInfoJson(const LogInfo& info);

}  // namespace roadslam::can

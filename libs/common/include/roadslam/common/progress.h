#pragma once
/// \file progress.h
/// A one-line progress bar with rate and ETA on stderr, shown only when stderr is a terminal.
/// The total is counted in the measure known in advance: items (KITTI sweeps, experiment jobs), bytes
/// of the input file (a pcap or rawlog, whose sweeps are not counted before reading it), or simulated
/// seconds (the simulator's scenario duration). The line is a pure function (progressLine) of the
/// counts and the time so far, so it is tested without a terminal.

#include <chrono>
#include <cstddef>
#include <string>

namespace roadslam {

enum class ProgressMeasure { Items, Bytes, SimulatedSeconds };

/// The fraction done and the time left at the rate so far.
struct ProgressEstimate {
  double fraction = 0;  ///< done / total, clamped to [0, 1]; NaN when the total is unknown (<= 0)
  double eta_s = 0;     ///< elapsed * (1 - fraction) / fraction [s]; NaN when unknown or nothing done yet
};
ProgressEstimate estimateProgress(double done, double total, double elapsed_s);

/// One progress line (no carriage return), e.g.
///   Items, total 300:      "roadslam-map [#########                     ] 90/300, 9.8/s, ETA 21 s"
///   Items, total unknown:  "roadslam-map 90 frames, 9.8/s, 9 s"
///   Bytes:                 "roadslam-map [#####     ...] 41 % of 12.3 MB, 120 frames, 9.8/s, ETA 12 s"
///   SimulatedSeconds:      "roadslam-sim [####      ...] 12.3 of 60.0 s simulated, 4.1x real time, ETA 14 s"
/// \p done and \p total in the measure's unit; \p frames: items made so far (Bytes only).
std::string progressLine(const std::string& label, ProgressMeasure measure, double done, double total,
                         std::size_t frames, double elapsed_s);

class ProgressBar {
 public:
  /// \param total items expected (0 = unknown: no bar, count and rate only)
  ProgressBar(std::string label, size_t total) : ProgressBar(std::move(label), double(total), ProgressMeasure::Items) {}
  /// \param total in the unit of \p measure (0 = unknown)
  ProgressBar(std::string label, double total, ProgressMeasure measure);
  ~ProgressBar();
  /// Items done (ProgressMeasure::Items). Redraws at most 10 times a second.
  void update(size_t done) { update(double(done), done); }
  /// \p done in the measure's unit, with \p frames made so far.
  void update(double done, size_t frames);
  /// Draws the last state once more and ends the line (nothing when nothing was updated).
  void finish();
  bool enabled() const { return enabled_; }

 private:
  void draw(std::chrono::steady_clock::time_point now) const;

  std::string label_;
  double total_;
  ProgressMeasure measure_;
  bool enabled_;
  bool finished_ = false;
  bool updated_ = false;
  double done_ = 0;
  size_t frames_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace roadslam

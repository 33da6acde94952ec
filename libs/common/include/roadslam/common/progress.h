#pragma once
/// \file progress.h
/// A one-line progress bar with rate and ETA on stderr, shown only when stderr is a terminal.

#include <chrono>
#include <string>

namespace roadslam {

class ProgressBar {
 public:
  /// \param total items expected (0 = unknown: no bar, count and rate only)
  ProgressBar(std::string label, size_t total);
  ~ProgressBar();
  /// Redraws at most 10 times a second.
  void update(size_t done);
  void finish();
  bool enabled() const { return enabled_; }

 private:
  std::string label_;
  size_t total_;
  bool enabled_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace roadslam

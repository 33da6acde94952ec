#pragma once
// The progress bar of a job over its input, shared by roadslam-map and roadslam-bounds.
#include <optional>
#include <string>

#include "roadslam/common/progress.h"
#include "roadslam/sources/scan_source.h"

namespace roadslam::jobs {

/// Counts a job's frames against its input: of the sweeps when they are counted in advance (a KITTI
/// folder), else of the input's bytes read (a pcap, rawlog or session: their sweeps are not counted
/// before reading), else frames and rate alone (live). Nothing at all unless \p show (--quiet hides
/// it); ProgressBar draws only on a terminal.
class SourceProgress {
 public:
  SourceProgress(std::string label, const sources::ScanSource& source, bool show) : source_(source) {
    if (!show) return;
    const auto bytes = source.readProgress().bytes_total;
    by_bytes_ = source.sizeHint() == 0 && bytes > 0;
    if (by_bytes_) bar_.emplace(std::move(label), static_cast<double>(bytes), ProgressMeasure::Bytes);
    else bar_.emplace(std::move(label), source.sizeHint());
  }
  void update(size_t frames) {
    if (!bar_) return;
    if (by_bytes_) bar_->update(static_cast<double>(source_.readProgress().bytes_read), frames);
    else bar_->update(frames);
  }
  void finish() {
    if (bar_) bar_->finish();
  }

 private:
  const sources::ScanSource& source_;
  bool by_bytes_ = false;
  std::optional<ProgressBar> bar_;
};

}  // namespace roadslam::jobs

#include "roadslam/common/progress.h"

#include <unistd.h>

#include <cstdio>

namespace roadslam {

ProgressBar::ProgressBar(std::string label, size_t total)
    : label_(std::move(label)),
      total_(total),
      enabled_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(size_t done) {
  if (!enabled_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100) && done != total_) return;
  last_draw_ = now;
  const double el = std::chrono::duration<double>(now - start_).count();
  const double rate = el > 0 ? done / el : 0;
  if (total_ > 0) {
    constexpr int kWidth = 30;
    const int fill = static_cast<int>(kWidth * done / total_);
    const double eta = rate > 0 ? (total_ - done) / rate : 0;
    std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu %.1f/s ETA %.0f s ", label_.c_str(), fill,
                 "##############################", kWidth - fill, "", done, total_, rate, eta);
  } else {
    std::fprintf(stderr, "\r%s %zu frames, %.1f/s, %.0f s ", label_.c_str(), done, rate, el);
  }
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (enabled_ && !finished_) std::fprintf(stderr, "\n");
  finished_ = true;
}

}  // namespace roadslam

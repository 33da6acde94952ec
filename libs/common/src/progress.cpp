#include "roadslam/common/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace roadslam {
namespace {

constexpr int kBarWidth = 30;  // characters

std::string bar(double fraction) {
  const int fill = static_cast<int>(kBarWidth * fraction);
  return "[" + std::string(fill, '#') + std::string(kBarWidth - fill, ' ') + "]";
}

std::string eta(double eta_s) {
  char text[32];
  if (std::isnan(eta_s)) return "ETA ?";
  std::snprintf(text, sizeof text, "ETA %.0f s", eta_s);
  return text;
}

}  // namespace

ProgressEstimate estimateProgress(double done, double total, double elapsed_s) {
  ProgressEstimate e;
  if (!(total > 0)) return {std::nan(""), std::nan("")};
  e.fraction = std::clamp(done / total, 0.0, 1.0);
  // At the rate so far: the time per unit done times the units left.
  e.eta_s = e.fraction > 0 ? elapsed_s * (1 - e.fraction) / e.fraction : std::nan("");
  return e;
}

std::string progressLine(const std::string& label, ProgressMeasure measure, double done, double total,
                         std::size_t frames, double elapsed_s) {
  const ProgressEstimate e = estimateProgress(done, total, elapsed_s);
  const double per_s = elapsed_s > 0 ? done / elapsed_s : 0;
  char text[200];
  if (measure == ProgressMeasure::SimulatedSeconds && total > 0) {
    std::snprintf(text, sizeof text, " %.1f of %.1f s simulated, %.1fx real time, ", done, total, per_s);
    return label + " " + bar(e.fraction) + text + eta(e.eta_s);
  }
  if (measure == ProgressMeasure::Bytes && total > 0) {
    const double frames_per_s = elapsed_s > 0 ? static_cast<double>(frames) / elapsed_s : 0;
    std::snprintf(text, sizeof text, " %.0f %% of %.1f MB, %zu frames, %.1f/s, ", 100 * e.fraction, total / 1e6,
                  frames, frames_per_s);
    return label + " " + bar(e.fraction) + text + eta(e.eta_s);
  }
  if (total > 0) {
    std::snprintf(text, sizeof text, " %.0f/%.0f, %.1f/s, ", done, total, per_s);
    return label + " " + bar(e.fraction) + text + eta(e.eta_s);
  }
  std::snprintf(text, sizeof text, " %zu frames, %.1f/s, %.0f s", frames, static_cast<double>(frames) / std::max(elapsed_s, 1e-9),
                elapsed_s);
  return label + text;
}

ProgressBar::ProgressBar(std::string label, double total, ProgressMeasure measure)
    : label_(std::move(label)),
      total_(total),
      measure_(measure),
      enabled_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double done, size_t frames) {
  if (!enabled_ || finished_) return;
  done_ = done, frames_ = frames, updated_ = true;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100) && done < total_) return;
  last_draw_ = now;
  draw(now);
}

void ProgressBar::draw(std::chrono::steady_clock::time_point now) const {
  const double el = std::chrono::duration<double>(now - start_).count();
  // Trailing blanks wipe what a longer line before left.
  std::fprintf(stderr, "\r%s   ", progressLine(label_, measure_, done_, total_, frames_, el).c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (!updated_) return;  // nothing drawn: no line to end
  draw(std::chrono::steady_clock::now());  // where it ended, whatever the last redraw showed
  std::fprintf(stderr, "\n");
}

}  // namespace roadslam

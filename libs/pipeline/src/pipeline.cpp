#include "roadslam/pipeline/pipeline.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace roadslam::pipeline {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

/// A source whose first sweep was read ahead (openNonEmptySource); everything else is the source's.
class PeekedSource : public sources::ScanSource {
 public:
  PeekedSource(std::unique_ptr<sources::ScanSource> src, Scan first) : src_(std::move(src)), first_(std::move(first)) {}
  std::optional<Scan> next() override {
    if (first_) {
      std::optional<Scan> s = std::move(first_);
      first_.reset();
      return s;
    }
    return src_->next();
  }
  bool finished() const override { return !first_ && src_->finished(); }
  std::vector<gnss::GnssFix> takeGpsFixes() override { return src_->takeGpsFixes(); }
  std::string describe() const override { return src_->describe(); }
  sources::ScanSourceStats stats() const override { return src_->stats(); }
  size_t sizeHint() const override { return src_->sizeHint(); }
  std::string errorMessage() const override { return src_->errorMessage(); }
  uint64_t sweepsBeforeDamage() const override { return src_->sweepsBeforeDamage(); }
  std::vector<std::string> warnings() const override { return src_->warnings(); }
  sources::ReadProgress readProgress() const override { return src_->readProgress(); }
  std::optional<sources::LidarModelReport> lidarModel() const override { return src_->lidarModel(); }

 private:
  std::unique_ptr<sources::ScanSource> src_;
  std::optional<Scan> first_;
};

}  // namespace

double StageTimes::of(const std::string& stage) const {
  const auto it = by_stage.find(stage);
  return it == by_stage.end() ? 0.0 : it->second;
}

StageTimes& StageTimes::operator+=(const StageTimes& o) {
  source += o.source;
  for (const auto& [name, ms] : o.by_stage) by_stage[name] += ms;
  return *this;
}

Pipeline::Pipeline(std::unique_ptr<sources::ScanSource> source, StageList stages)
    : source_(std::move(source)), stages_(std::move(stages)) {
  if (!source_) throw std::invalid_argument("Pipeline: no source");
  poses_ = stages_.empty() ? nullptr : dynamic_cast<PoseStage*>(stages_.front().get());
  if (!poses_) throw std::invalid_argument("Pipeline: no pose stage first");
  for (const auto& s : stages_) keep_sweep_ = keep_sweep_ || s->readsSweep();
  poses_->leaveSweep(keep_sweep_);
}

Pipeline::~Pipeline() = default;

void Pipeline::finish() {
  for (const auto& s : stages_) s->finish();
}

std::optional<PipelineFrame> Pipeline::next() {
  PipelineFrame f;
  auto t = Clock::now();
  f.scan = source_->next();
  f.ms.source = msSince(t);
  if (!f.scan) {
    if (source_->finished()) finish();
    return std::nullopt;
  }
  f.index = frames_++;
  for (const auto& s : stages_) {
    t = Clock::now();
    s->process(f);
    f.ms.by_stage[s->name()] += msSince(t);
  }
  if (!keep_sweep_) f.scan.reset();
  totals_ += f.ms;
  return f;
}

std::unique_ptr<sources::ScanSource> openNonEmptySource(const std::string& path, const mrpt::config::CConfigFileBase& cfg,
                                                        const std::string& times_path, double* first_stamp_s) {
  auto src = sources::openScanSource(path, cfg, times_path);
  std::optional<Scan> first = src->next();
  if (!first) {
    const std::string err = src->errorMessage();
    throw std::runtime_error("input '" + path + "' gives no sweep" + (err.empty() ? "" : ": " + err));
  }
  if (first_stamp_s) *first_stamp_s = first->stamp_s;
  return std::make_unique<PeekedSource>(std::move(src), std::move(*first));
}

}  // namespace roadslam::pipeline

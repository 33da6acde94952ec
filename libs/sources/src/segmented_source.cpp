#include "roadslam/sources/segmented_source.h"

#include <filesystem>
#include <stdexcept>

namespace roadslam::sources {
namespace {
// Adds \p b's counters to \p a (stamps are the caller's).
void addCounts(SourceStats& a, const SourceStats& b) {
  a.packets += b.packets;
  a.data_packets += b.data_packets;
  a.position_packets += b.position_packets;
  a.malformed_packets += b.malformed_packets;
  a.skipped_packets += b.skipped_packets;
  a.missing_packets += b.missing_packets;
  a.kernel_drops += b.kernel_drops;
}
}  // namespace

SegmentedPacketSource::SegmentedPacketSource(std::vector<std::string> segments, const PortConfig& ports)
    : segments_(std::move(segments)), ports_(ports) {
  if (segments_.empty()) throw std::runtime_error("a rawlog session needs at least one segment");
  for (const auto& s : segments_) {
    std::error_code ec;
    const auto n = std::filesystem::file_size(s, ec);
    bytes_total_ += ec ? 0 : n;
  }
  source_ = std::make_unique<RawlogPacketSource>(segments_.front(), ports_);
}

SegmentedPacketSource::~SegmentedPacketSource() = default;

std::string SegmentedPacketSource::describe() const {
  return "rawlog session:" + std::filesystem::path(segments_.front()).parent_path().string() + " (" +
         std::to_string(segments_.size()) + " segments)";
}

bool SegmentedPacketSource::finished() const { return !source_; }

ReadProgress SegmentedPacketSource::readProgress() const {
  return {bytes_done_ + (source_ ? source_->readProgress().bytes_read : 0), bytes_total_};
}

void SegmentedPacketSource::closeCurrent() {
  addCounts(done_, source_->stats());
  bytes_done_ += source_->readProgress().bytes_total;
  for (auto& f : source_->takeDecodedFixes()) fixes_.push_back(f);
  if (!source_->errorMessage().empty())
    error_ += (error_.empty() ? "" : "; ") + source_->errorMessage();
  source_.reset();
  if (++current_ < segments_.size()) source_ = std::make_unique<RawlogPacketSource>(segments_[current_], ports_);
}

std::optional<velodyne::RawPacket> SegmentedPacketSource::next() {
  while (source_) {
    auto p = source_->next();
    const SourceStats& s = source_->stats();
    const double first = stats_.packets ? stats_.first_stamp_s : 0.0, last = stats_.last_stamp_s;
    stats_ = done_;
    addCounts(stats_, s);
    stats_.first_stamp_s = first ? first : s.first_stamp_s;
    stats_.last_stamp_s = s.packets ? s.last_stamp_s : last;  // a new segment has none yet
    if (p) return p;
    if (!source_->finished()) return std::nullopt;
    closeCurrent();
  }
  return std::nullopt;
}

std::vector<gnss::GnssFix> SegmentedPacketSource::takeDecodedFixes() {
  if (source_)
    for (auto& f : source_->takeDecodedFixes()) fixes_.push_back(f);
  std::vector<gnss::GnssFix> out;
  out.swap(fixes_);
  return out;
}

}  // namespace roadslam::sources

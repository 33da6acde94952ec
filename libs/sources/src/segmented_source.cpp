#include "roadslam/sources/segmented_source.h"

#include <filesystem>
#include <stdexcept>

namespace roadslam::sources {

SegmentedPacketSource::SegmentedPacketSource(std::vector<std::string> segments, const PortConfig& ports)
    : segments_(std::move(segments)), ports_(ports) {
  if (segments_.empty()) throw std::runtime_error("a rawlog session needs at least one segment");
  source_ = std::make_unique<RawlogPacketSource>(segments_.front(), ports_);
}

SegmentedPacketSource::~SegmentedPacketSource() = default;

std::string SegmentedPacketSource::describe() const {
  return "rawlog session:" + std::filesystem::path(segments_.front()).parent_path().string() + " (" +
         std::to_string(segments_.size()) + " segments)";
}

bool SegmentedPacketSource::finished() const { return !source_; }

void SegmentedPacketSource::closeCurrent() {
  const SourceStats& s = source_->stats();
  done_.packets += s.packets;
  done_.data_packets += s.data_packets;
  done_.position_packets += s.position_packets;
  done_.malformed_packets += s.malformed_packets;
  done_.skipped_packets += s.skipped_packets;
  done_.missing_packets += s.missing_packets;
  done_.kernel_drops += s.kernel_drops;
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
    const double first = stats_.packets ? stats_.first_stamp_s : 0.0;
    stats_ = done_;
    stats_.packets += s.packets;
    stats_.data_packets += s.data_packets;
    stats_.position_packets += s.position_packets;
    stats_.malformed_packets += s.malformed_packets;
    stats_.skipped_packets += s.skipped_packets;
    stats_.missing_packets += s.missing_packets;
    stats_.kernel_drops += s.kernel_drops;
    stats_.first_stamp_s = first ? first : s.first_stamp_s;
    if (s.packets) stats_.last_stamp_s = s.last_stamp_s;
    if (p) return p;
    if (!source_->finished()) return std::nullopt;
    closeCurrent();
  }
  return std::nullopt;
}

std::vector<TimedGpsFix> SegmentedPacketSource::takeDecodedFixes() {
  if (source_)
    for (auto& f : source_->takeDecodedFixes()) fixes_.push_back(f);
  std::vector<TimedGpsFix> out;
  out.swap(fixes_);
  return out;
}

}  // namespace roadslam::sources

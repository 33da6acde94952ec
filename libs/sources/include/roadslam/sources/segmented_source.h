#pragma once
/// \file segmented_source.h
/// The packets of a recording cut into rawlog segments (a roadslam-grab session folder:
/// <prefix>_000.rawlog, _001, ...) read one segment after the other as one stream, so every job
/// (roadslam-map, roadslam-bounds, the viewer's --run-slam, experiments) takes the session folder
/// as its input. A damaged segment (a crash cut its end) is read up to the damage, named in
/// errorMessage(), and reading goes on with the next one.

#include <memory>
#include <string>
#include <vector>

#include "roadslam/sources/rawlog_source.h"

namespace roadslam::sources {

class SegmentedPacketSource : public PacketSource {
 public:
  /// \p segments in time order (RawlogSession::segmentsOf); throws naming one that cannot be opened,
  /// or when the list is empty.
  explicit SegmentedPacketSource(std::vector<std::string> segments, const PortConfig& ports = {});
  ~SegmentedPacketSource() override;

  std::optional<velodyne::RawPacket> next() override;
  bool finished() const override;
  const SourceStats& stats() const override { return stats_; }
  /// "rawlog session:FOLDER (N segments)".
  std::string describe() const override;
  /// Every damaged segment, one after the other ("; "-separated).
  std::string errorMessage() const override { return error_; }
  std::vector<gnss::GnssFix> takeDecodedFixes() override;
  /// Bytes of the segments read (the closed ones whole) of their sum.
  ReadProgress readProgress() const override;

 private:
  void closeCurrent();

  std::vector<std::string> segments_;
  PortConfig ports_;
  std::size_t current_ = 0;
  std::unique_ptr<RawlogPacketSource> source_;
  SourceStats stats_, done_;  // done_: the closed segments' sums
  uint64_t bytes_total_ = 0, bytes_done_ = 0;  // all segments' sizes, the closed ones' [bytes]
  std::vector<gnss::GnssFix> fixes_;
  std::string error_;
};

}  // namespace roadslam::sources

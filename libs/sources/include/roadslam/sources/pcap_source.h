#pragma once
/// \file pcap_source.h
/// Replays a libpcap capture of Velodyne traffic through libs/pcap's PcapReader, keeping the
/// capture timestamps (unlike MRPT's CVelodyneScanner, which replaces them by the host clock).

#include <memory>
#include <string>

#include "roadslam/sources/packet_source.h"

namespace roadslam::pcap {
class PcapReader;
}

namespace roadslam::sources {

class PcapPacketSource : public PacketSource {
 public:
  /// Opens \p path; throws std::runtime_error naming the file when it is missing, empty or not a
  /// capture (from PcapReader).
  explicit PcapPacketSource(const std::string& path, const PortConfig& ports = {});
  ~PcapPacketSource() override;

  /// Data and position payloads; other UDP traffic and non-UDP records are counted as skipped,
  /// wrong-size payloads on the Velodyne ports as malformed.
  std::optional<velodyne::RawPacket> next() override;
  bool finished() const override { return finished_; }
  const SourceStats& stats() const override { return stats_; }
  std::string describe() const override { return "pcap:" + path_; }
  /// Empty unless the capture is damaged (truncated mid-record); names the file and record.
  std::string errorMessage() const override;
  ReadProgress readProgress() const override;

 private:
  std::unique_ptr<pcap::PcapReader> reader_;
  std::string path_;
  PortConfig ports_;
  SourceStats stats_;
  GapCounter gaps_;
  bool finished_ = false;
};

}  // namespace roadslam::sources

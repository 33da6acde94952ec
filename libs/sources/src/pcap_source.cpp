#include "roadslam/sources/pcap_source.h"

#include "roadslam/pcap/pcap_reader.h"

namespace roadslam::sources {

PcapPacketSource::PcapPacketSource(const std::string& path, const PortConfig& ports)
    : reader_(std::make_unique<pcap::PcapReader>(path)), path_(path), ports_(ports), gaps_(0, ports.model) {}

PcapPacketSource::~PcapPacketSource() = default;

std::string PcapPacketSource::errorMessage() const { return reader_->errorMessage(); }

ReadProgress PcapPacketSource::readProgress() const { return {reader_->bytesRead(), reader_->fileSize()}; }

std::optional<velodyne::RawPacket> PcapPacketSource::next() {
  pcap::UdpDatagram d;
  while (!finished_) {
    if (reader_->next(d) != pcap::ReadStatus::Ok) {
      finished_ = true;
      // Records that never became datagrams (non-UDP, fragments, truncated) are skipped traffic.
      const auto& rs = reader_->stats();
      stats_.skipped_packets += rs.non_udp + rs.fragments + rs.truncated_records;
      break;
    }
    velodyne::RawPacket p;
    p.stamp_s = d.stamp_s;
    p.dst_port = d.dst_port;
    p.src_ip = d.src_ip;
    p.payload = std::move(d.payload);
    if (accountPacket(ports_, p, stats_, gaps_)) return p;
  }
  return std::nullopt;
}

}  // namespace roadslam::sources

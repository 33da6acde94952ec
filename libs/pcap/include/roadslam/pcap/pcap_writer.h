#pragma once
/// \file pcap_writer.h
/// Writes UDP payloads into a classic libpcap file (LINKTYPE_ETHERNET, microsecond stamps: the
/// format every tool reads) with synthetic Ethernet/IPv4/UDP headers, readable by tcpdump, Wireshark, VeloView and
/// our own PcapReader. The capture format is the replay format.

#include <cstdint>
#include <memory>
#include <string>

namespace roadslam::pcap {

class PcapWriter {
 public:
  /// Creates (truncates) \p path; throws std::runtime_error "cannot write 'NAME': REASON" on any
  /// failure, NAME = \p name (the final file when \p path is a temporary one) or \p path.
  explicit PcapWriter(const std::string& path, const std::string& name = "");
  ~PcapWriter();
  PcapWriter(const PcapWriter&) = delete;
  PcapWriter& operator=(const PcapWriter&) = delete;

  /// Appends one UDP datagram. \p stamp_s is the capture time [s since epoch].
  /// Source address defaults to 192.168.1.201 (the VLP-16 factory address).
  void writeUdp(double stamp_s, uint16_t src_port, uint16_t dst_port, const uint8_t* payload,
                std::size_t size, uint32_t src_ip = 0xC0A801C9u, uint32_t dst_ip = 0xFFFFFFFFu);
  void flush();
  /// Flushes and closes; further writes throw.
  void close();
  std::size_t packetsWritten() const { return packets_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t packets_ = 0;
};

}  // namespace roadslam::pcap

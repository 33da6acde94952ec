#pragma once
/// \file pcap_reader.h
/// Reads IPv4/UDP datagrams from a libpcap capture (classic or pcapng, whatever libpcap opens),
/// keeping the capture timestamps (nanosecond precision when the file has it).
///
/// Link types: Ethernet (with any number of 802.1Q / 802.1ad VLAN tags), Linux cooked v1 (SLL) and
/// v2 (SLL2), raw IPv4 (LINKTYPE_RAW / LINKTYPE_IPV4), BSD loopback (LINKTYPE_NULL).
/// Only unfragmented IPv4 UDP is returned; everything else is counted and skipped.
///
/// This library sits below libs/velodyne in the data flow, so it has its own generic UdpDatagram;
/// libs/sources turns it into a velodyne::RawPacket (same fields).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace roadslam::pcap {

/// One UDP datagram as captured.
struct UdpDatagram {
  double stamp_s = 0;      ///< capture time [s since epoch, as recorded in the file]; ~0.5 us resolution
  int64_t stamp_ns = 0;    ///< the same capture time, exact [ns since epoch]
  uint32_t src_ip = 0;     ///< IPv4 source address, host byte order
  uint32_t dst_ip = 0;     ///< IPv4 destination address, host byte order
  uint16_t src_port = 0;   ///< UDP source port
  uint16_t dst_port = 0;   ///< UDP destination port
  std::vector<uint8_t> payload;  ///< UDP payload bytes
};

/// What the reader saw so far. Every capture record lands in exactly one of the counters
/// datagrams / non_udp / fragments / truncated_records / unsupported_link.
struct PcapReadStats {
  std::size_t records = 0;            ///< capture records read
  std::size_t datagrams = 0;          ///< IPv4 UDP datagrams returned
  std::size_t non_udp = 0;            ///< other protocols: IPv6, ARP, TCP, ICMP, ... (skipped)
  std::size_t fragments = 0;          ///< IPv4 fragments (skipped, not reassembled)
  std::size_t truncated_records = 0;  ///< records cut by the snap length or malformed headers
};

enum class ReadStatus {
  Ok,         ///< a datagram was returned
  EndOfFile,  ///< clean end of the capture
  Error       ///< the file is damaged (e.g. truncated mid-record): see errorMessage()
};

/// Sequential reader. Usage: `PcapReader r(path); UdpDatagram d; while (r.next(d) == ReadStatus::Ok) ...`
/// then check `r.status()` / `r.errorMessage()`. Never throws after construction.
class PcapReader {
 public:
  /// Opens \p path. Throws std::runtime_error naming the file when it is missing, empty, not a
  /// capture, or of an unsupported link type.
  explicit PcapReader(const std::string& path);
  ~PcapReader();
  PcapReader(const PcapReader&) = delete;
  PcapReader& operator=(const PcapReader&) = delete;

  /// Reads up to the next IPv4 UDP datagram into \p out (its payload buffer is reused).
  ReadStatus next(UdpDatagram& out);

  ReadStatus status() const { return status_; }
  /// Empty unless status() == Error; names the file and the 0-based record index.
  const std::string& errorMessage() const { return error_; }
  const PcapReadStats& stats() const { return stats_; }
  int linkType() const;               ///< DLT_* value of the capture
  /// Bytes of the file read so far (where the next record starts) and the file's size [bytes]: the
  /// progress of a replay whose records are not counted in advance.
  uint64_t bytesRead() const;
  uint64_t fileSize() const;
  const std::string& path() const { return path_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  std::string error_;
  ReadStatus status_ = ReadStatus::Ok;
  PcapReadStats stats_;
};

/// Reads every datagram (optionally only those to \p dst_port, 0 = all). Throws at open like
/// PcapReader; on a damaged file returns the datagrams up to the damage and fills \p error.
std::vector<UdpDatagram> readUdpDatagrams(const std::string& path, uint16_t dst_port = 0,
                                          std::string* error = nullptr,
                                          PcapReadStats* stats = nullptr);

}  // namespace roadslam::pcap

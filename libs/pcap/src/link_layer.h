#pragma once
// Link-layer + IPv4 + UDP parsing of one capture record. Internal to libs/pcap; pure function, no
// allocation, so it is also the fuzzing surface.

#include <cstddef>
#include <cstdint>

namespace roadslam::pcap::link {

enum class Kind { Udp, Fragment, Truncated, Other };

struct Parsed {
  Kind kind = Kind::Other;
  uint32_t src_ip = 0, dst_ip = 0;
  uint16_t src_port = 0, dst_port = 0;
  const uint8_t* payload = nullptr;
  std::size_t payload_size = 0;
};

bool isSupported(int dlt);

/// \p caplen bytes are present of an original frame of \p wire_len bytes.
Parsed parseFrame(int dlt, const uint8_t* data, std::size_t caplen, std::size_t wire_len);

}  // namespace roadslam::pcap::link

#pragma once
// Byte-level helpers for Ethernet II / IPv4 (RFC 791) / UDP (RFC 768) headers. Internal to libs/pcap.

#include <cstddef>
#include <cstdint>

namespace roadslam::pcap::net {

constexpr std::size_t kEthHeader = 14;
constexpr std::size_t kIpv4Header = 20;
constexpr std::size_t kUdpHeader = 8;
constexpr std::size_t kMaxUdpPayload = 65535 - kIpv4Header - kUdpHeader;
constexpr uint16_t kEtherTypeIpv4 = 0x0800;
constexpr uint16_t kEtherTypeIpv6 = 0x86DD;
constexpr uint16_t kEtherTypeVlan = 0x8100;
constexpr uint16_t kEtherTypeQinQ = 0x88A8;
constexpr uint8_t kIpProtoUdp = 17;

inline void putLe16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v);
  p[1] = static_cast<uint8_t>(v >> 8);
}
inline void putLe32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (8 * i));
}
inline void putBe16(uint8_t* p, uint16_t v) {
  p[0] = static_cast<uint8_t>(v >> 8);
  p[1] = static_cast<uint8_t>(v);
}
inline void putBe32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<uint8_t>(v >> (24 - 8 * i));
}
inline uint16_t getBe16(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }
inline uint32_t getBe32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

/// RFC 791 header checksum: one's complement of the one's-complement sum of 16-bit words.
uint16_t ipv4Checksum(const uint8_t* hdr, std::size_t len);

/// Writes Ethernet (broadcast dst, Velodyne OUI src) + IPv4 (DF, TTL 64) + UDP (no checksum,
/// allowed by RFC 768 over IPv4) headers for a payload of \p payload_size bytes.
void writeEthIpv4UdpHeaders(uint8_t* out, std::size_t payload_size, uint32_t src_ip,
                            uint32_t dst_ip, uint16_t src_port, uint16_t dst_port, uint16_t ip_id);

}  // namespace roadslam::pcap::net

#include "net_headers.h"

namespace roadslam::pcap::net {

uint16_t ipv4Checksum(const uint8_t* hdr, std::size_t len) {
  uint32_t sum = 0;
  for (std::size_t i = 0; i + 1 < len; i += 2) sum += getBe16(hdr + i);
  while (sum >> 16) sum = (sum & 0xFFFF) + (sum >> 16);
  return static_cast<uint16_t>(~sum & 0xFFFF);
}

void writeEthIpv4UdpHeaders(uint8_t* out, std::size_t payload_size, uint32_t src_ip,
                            uint32_t dst_ip, uint16_t src_port, uint16_t dst_port, uint16_t ip_id) {
  static constexpr uint8_t kDstMac[6] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  static constexpr uint8_t kSrcMac[6] = {0x60, 0x76, 0x88, 0x00, 0x00, 0x01};  // Velodyne OUI
  for (int i = 0; i < 6; ++i) {
    out[i] = kDstMac[i];
    out[6 + i] = kSrcMac[i];
  }
  putBe16(out + 12, kEtherTypeIpv4);
  uint8_t* ip = out + kEthHeader;
  ip[0] = 0x45;  // version 4, IHL 5 words
  ip[1] = 0;
  putBe16(ip + 2, static_cast<uint16_t>(kIpv4Header + kUdpHeader + payload_size));
  putBe16(ip + 4, ip_id);
  putBe16(ip + 6, 0x4000);  // don't fragment
  ip[8] = 64;
  ip[9] = kIpProtoUdp;
  putBe16(ip + 10, 0);
  putBe32(ip + 12, src_ip);
  putBe32(ip + 16, dst_ip);
  putBe16(ip + 10, ipv4Checksum(ip, kIpv4Header));
  uint8_t* udp = ip + kIpv4Header;
  putBe16(udp, src_port);
  putBe16(udp + 2, dst_port);
  putBe16(udp + 4, static_cast<uint16_t>(kUdpHeader + payload_size));
  putBe16(udp + 6, 0);
}

}  // namespace roadslam::pcap::net

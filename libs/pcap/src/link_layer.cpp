#include "link_layer.h"

#include <pcap/dlt.h>

#include "net_headers.h"

namespace roadslam::pcap::link {
namespace {

constexpr std::size_t kSllHeader = 16;   // https://www.tcpdump.org/linktypes/LINKTYPE_LINUX_SLL.html
constexpr std::size_t kSll2Header = 20;  // https://www.tcpdump.org/linktypes/LINKTYPE_LINUX_SLL2.html
constexpr std::size_t kNullHeader = 4;   // LINKTYPE_NULL: host-order u32 address family
constexpr std::size_t kVlanTag = 4;
constexpr int kDltIpv4 = 228;            // LINKTYPE_IPV4
constexpr int kDltSll2 = 276;            // LINKTYPE_LINUX_SLL2
constexpr uint32_t kAfInet = 2;

/// Finds where the IPv4 header starts, or returns false with the kind of the frame.
bool locateIpv4(int dlt, const uint8_t* d, std::size_t n, std::size_t& off, Kind& kind) {
  uint16_t ethertype = 0;
  switch (dlt) {
    case DLT_EN10MB:
      off = net::kEthHeader;
      if (n < off) return kind = Kind::Truncated, false;
      ethertype = net::getBe16(d + 12);
      while (ethertype == net::kEtherTypeVlan || ethertype == net::kEtherTypeQinQ) {
        if (n < off + kVlanTag) return kind = Kind::Truncated, false;
        ethertype = net::getBe16(d + off + 2);
        off += kVlanTag;
      }
      break;
    case DLT_LINUX_SLL:
      off = kSllHeader;
      if (n < off) return kind = Kind::Truncated, false;
      ethertype = net::getBe16(d + 14);
      break;
    case kDltSll2:
      off = kSll2Header;
      if (n < off) return kind = Kind::Truncated, false;
      ethertype = net::getBe16(d);
      break;
    case DLT_NULL:
      off = kNullHeader;
      if (n < off) return kind = Kind::Truncated, false;
      // Host byte order of the capturing machine: accept AF_INET written either way.
      ethertype = (d[0] == kAfInet || d[3] == kAfInet) ? net::kEtherTypeIpv4 : 0;
      break;
    case DLT_RAW:
    case kDltIpv4:
      off = 0;
      if (n < 1) return kind = Kind::Truncated, false;
      ethertype = (d[0] >> 4) == 4 ? net::kEtherTypeIpv4 : 0;
      break;
    default: return kind = Kind::Other, false;
  }
  if (ethertype != net::kEtherTypeIpv4) return kind = Kind::Other, false;
  return true;
}

}  // namespace

bool isSupported(int dlt) {
  return dlt == DLT_EN10MB || dlt == DLT_LINUX_SLL || dlt == kDltSll2 || dlt == DLT_RAW ||
         dlt == kDltIpv4 || dlt == DLT_NULL;
}

Parsed parseFrame(int dlt, const uint8_t* d, std::size_t caplen, std::size_t wire_len) {
  Parsed p;
  if (caplen < wire_len) return p.kind = Kind::Truncated, p;  // cut by the snap length
  std::size_t off = 0;
  if (!locateIpv4(dlt, d, caplen, off, p.kind)) return p;
  // RFC 791 header.
  if (caplen < off + net::kIpv4Header) return p.kind = Kind::Truncated, p;
  const uint8_t* ip = d + off;
  if ((ip[0] >> 4) != 4) return p.kind = Kind::Other, p;
  const std::size_t ihl = static_cast<std::size_t>(ip[0] & 0x0F) * 4;
  const std::size_t total = net::getBe16(ip + 2);
  if (ihl < net::kIpv4Header || total < ihl || caplen < off + total)
    return p.kind = Kind::Truncated, p;
  const uint16_t frag = net::getBe16(ip + 6);
  if ((frag & 0x2000) != 0 || (frag & 0x1FFF) != 0) return p.kind = Kind::Fragment, p;
  if (ip[9] != net::kIpProtoUdp) return p.kind = Kind::Other, p;
  // RFC 768 header.
  const uint8_t* udp = ip + ihl;
  if (total < ihl + net::kUdpHeader) return p.kind = Kind::Truncated, p;
  const std::size_t udp_len = net::getBe16(udp + 4);
  if (udp_len < net::kUdpHeader || udp_len > total - ihl) return p.kind = Kind::Truncated, p;
  p.kind = Kind::Udp;
  p.src_ip = net::getBe32(ip + 12);
  p.dst_ip = net::getBe32(ip + 16);
  p.src_port = net::getBe16(udp);
  p.dst_port = net::getBe16(udp + 2);
  p.payload = udp + net::kUdpHeader;
  p.payload_size = udp_len - net::kUdpHeader;
  return p;
}

}  // namespace roadslam::pcap::link

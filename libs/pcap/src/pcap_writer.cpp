#include "roadslam/pcap/pcap_writer.h"

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "net_headers.h"

namespace roadslam::pcap {

struct PcapWriter::Impl {
  std::string path, name;  // name: the file errors name (the final file of a temporary one)
  std::FILE* file = nullptr;
  uint16_t ip_id = 0;
  std::vector<uint8_t> buf;
};

namespace {

/// "cannot write 'NAME': REASON", the reason from errno (fwrite/fflush/fclose set it).
[[noreturn]] void fail(const std::string& name, const std::string& what) {
  const int err = errno;
  throw std::runtime_error(what + " '" + name + "': " + (err ? std::strerror(err) : "write error"));
}

}  // namespace

PcapWriter::PcapWriter(const std::string& path, const std::string& name) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->name = name.empty() ? path : name;
  errno = 0;
  impl_->file = std::fopen(path.c_str(), "wb");
  if (impl_->file == nullptr) fail(impl_->name, "cannot create");
  // Classic libpcap global header (pcap-savefile(5)): microsecond stamps, LINKTYPE_ETHERNET.
  uint8_t hdr[24];
  net::putLe32(hdr, 0xA1B2C3D4u);
  net::putLe16(hdr + 4, 2);
  net::putLe16(hdr + 6, 4);
  net::putLe32(hdr + 8, 0);   // thiszone
  net::putLe32(hdr + 12, 0);  // sigfigs
  net::putLe32(hdr + 16, 65535);
  net::putLe32(hdr + 20, 1);  // LINKTYPE_ETHERNET
  if (std::fwrite(hdr, 1, sizeof hdr, impl_->file) != sizeof hdr) fail(impl_->name, "cannot write");
}

PcapWriter::~PcapWriter() {
  if (impl_ && impl_->file != nullptr) std::fclose(impl_->file);
}

void PcapWriter::writeUdp(double stamp_s, uint16_t src_port, uint16_t dst_port,
                          const uint8_t* payload, std::size_t size, uint32_t src_ip,
                          uint32_t dst_ip) {
  if (impl_->file == nullptr) throw std::runtime_error("PcapWriter: write after close on '" + impl_->name + "'");
  if (size > net::kMaxUdpPayload) throw std::runtime_error("PcapWriter: UDP payload too large for '" + impl_->name + "'");
  const std::size_t frame_len = net::kEthHeader + net::kIpv4Header + net::kUdpHeader + size;
  auto& b = impl_->buf;
  b.assign(16 + frame_len, 0);
  double sec = std::floor(stamp_s);
  long usec = std::lround((stamp_s - sec) * 1e6);
  if (usec >= 1000000) {
    usec -= 1000000;
    sec += 1;
  }
  net::putLe32(b.data(), static_cast<uint32_t>(sec));
  net::putLe32(b.data() + 4, static_cast<uint32_t>(usec));
  net::putLe32(b.data() + 8, static_cast<uint32_t>(frame_len));
  net::putLe32(b.data() + 12, static_cast<uint32_t>(frame_len));
  net::writeEthIpv4UdpHeaders(b.data() + 16, size, src_ip, dst_ip, src_port, dst_port,
                              impl_->ip_id++);
  std::copy(payload, payload + size, b.data() + 16 + frame_len - size);
  if (std::fwrite(b.data(), 1, b.size(), impl_->file) != b.size())
    fail(impl_->name, "cannot write");
  ++packets_;
}

void PcapWriter::flush() {
  if (impl_->file != nullptr && std::fflush(impl_->file) != 0) fail(impl_->name, "cannot write");
}

void PcapWriter::close() {
  if (impl_->file == nullptr) return;
  const int rc = std::fclose(impl_->file);
  impl_->file = nullptr;
  if (rc != 0) fail(impl_->name, "cannot write");
}

}  // namespace roadslam::pcap

#include "roadslam/pcap/pcap_writer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "net_headers.h"

namespace roadslam::pcap {

struct PcapWriter::Impl {
  std::string path;
  std::FILE* file = nullptr;
  uint16_t ip_id = 0;
  std::vector<uint8_t> buf;
};

namespace {

void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("PcapWriter: " + what + " '" + path + "'");
}

}  // namespace

PcapWriter::PcapWriter(const std::string& path) : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->file = std::fopen(path.c_str(), "wb");
  if (impl_->file == nullptr) fail(path, "cannot create");
  // Classic libpcap global header (pcap-savefile(5)): microsecond stamps, LINKTYPE_ETHERNET.
  uint8_t hdr[24];
  net::putLe32(hdr, 0xA1B2C3D4u);
  net::putLe16(hdr + 4, 2);
  net::putLe16(hdr + 6, 4);
  net::putLe32(hdr + 8, 0);   // thiszone
  net::putLe32(hdr + 12, 0);  // sigfigs
  net::putLe32(hdr + 16, 65535);
  net::putLe32(hdr + 20, 1);  // LINKTYPE_ETHERNET
  if (std::fwrite(hdr, 1, sizeof hdr, impl_->file) != sizeof hdr) fail(path, "cannot write to");
}

PcapWriter::~PcapWriter() {
  if (impl_ && impl_->file != nullptr) std::fclose(impl_->file);
}

void PcapWriter::writeUdp(double stamp_s, uint16_t src_port, uint16_t dst_port,
                          const uint8_t* payload, std::size_t size, uint32_t src_ip,
                          uint32_t dst_ip) {
  if (impl_->file == nullptr) fail(impl_->path, "write after close on");
  if (size > net::kMaxUdpPayload) fail(impl_->path, "UDP payload too large for");
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
    fail(impl_->path, "cannot write to");
  ++packets_;
}

void PcapWriter::flush() {
  if (impl_->file != nullptr && std::fflush(impl_->file) != 0) fail(impl_->path, "cannot flush");
}

void PcapWriter::close() {
  if (impl_->file == nullptr) return;
  const int rc = std::fclose(impl_->file);
  impl_->file = nullptr;
  if (rc != 0) fail(impl_->path, "cannot close");
}

}  // namespace roadslam::pcap

#include "roadslam/pcap/pcap_reader.h"

#include <pcap/pcap.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "link_layer.h"

namespace roadslam::pcap {

struct PcapReader::Impl {
  pcap_t* handle = nullptr;
  int dlt = 0;
  bool nano = false;
};

PcapReader::PcapReader(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path) {
  char errbuf[PCAP_ERRBUF_SIZE] = {0};
  impl_->handle =
      pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO, errbuf);
  if (impl_->handle == nullptr)
    throw std::runtime_error("PcapReader: cannot open '" + path + "': " + errbuf);
  impl_->nano = pcap_get_tstamp_precision(impl_->handle) == PCAP_TSTAMP_PRECISION_NANO;
  impl_->dlt = pcap_datalink(impl_->handle);
  if (!link::isSupported(impl_->dlt)) {
    const char* name = pcap_datalink_val_to_name(impl_->dlt);
    pcap_close(impl_->handle);
    impl_->handle = nullptr;
    throw std::runtime_error("PcapReader: unsupported link type " + std::to_string(impl_->dlt) +
                             " (" + (name ? name : "?") + ") in '" + path + "'");
  }
}

PcapReader::~PcapReader() {
  if (impl_ && impl_->handle != nullptr) pcap_close(impl_->handle);
}

int PcapReader::linkType() const { return impl_->dlt; }

uint64_t PcapReader::bytesRead() const {
  FILE* f = impl_->handle ? pcap_file(impl_->handle) : nullptr;
  const long at = f ? std::ftell(f) : -1;
  return at > 0 ? static_cast<uint64_t>(at) : 0;
}

uint64_t PcapReader::fileSize() const {
  std::error_code ec;
  const auto n = std::filesystem::file_size(path_, ec);
  return ec ? 0 : static_cast<uint64_t>(n);
}

ReadStatus PcapReader::next(UdpDatagram& out) {
  if (status_ != ReadStatus::Ok) return status_;
  for (;;) {
    pcap_pkthdr* hdr = nullptr;
    const u_char* data = nullptr;
    FILE* f = pcap_file(impl_->handle);
    const long at = f ? std::ftell(f) : -1;  // where the record starts (stdio accounts for its buffer)
    const int rc = pcap_next_ex(impl_->handle, &hdr, &data);
    if (rc == PCAP_ERROR_BREAK) return status_ = ReadStatus::EndOfFile;
    if (rc != 1) {
      error_ = "PcapReader: '" + path_ + "' damaged at record " + std::to_string(stats_.records) +
               (at >= 0 ? " (byte " + std::to_string(at) + ")" : "") + ": " + pcap_geterr(impl_->handle);
      return status_ = ReadStatus::Error;
    }
    ++stats_.records;
    const link::Parsed p = link::parseFrame(impl_->dlt, data, hdr->caplen, hdr->len);
    switch (p.kind) {
      case link::Kind::Udp: break;
      case link::Kind::Fragment: ++stats_.fragments; continue;
      case link::Kind::Truncated: ++stats_.truncated_records; continue;
      case link::Kind::Other: ++stats_.non_udp; continue;
    }
    // With PCAP_TSTAMP_PRECISION_NANO, libpcap puts nanoseconds in tv_usec (pcap_open_offline(3)).
    const int64_t frac_ns = static_cast<int64_t>(hdr->ts.tv_usec) * (impl_->nano ? 1 : 1000);
    out.stamp_ns = static_cast<int64_t>(hdr->ts.tv_sec) * 1000000000LL + frac_ns;
    out.stamp_s = static_cast<double>(hdr->ts.tv_sec) + static_cast<double>(frac_ns) * 1e-9;
    out.src_ip = p.src_ip;
    out.dst_ip = p.dst_ip;
    out.src_port = p.src_port;
    out.dst_port = p.dst_port;
    out.payload.assign(p.payload, p.payload + p.payload_size);
    ++stats_.datagrams;
    return ReadStatus::Ok;
  }
}

std::vector<UdpDatagram> readUdpDatagrams(const std::string& path, uint16_t dst_port,
                                          std::string* error, PcapReadStats* stats) {
  PcapReader reader(path);
  std::vector<UdpDatagram> out;
  UdpDatagram d;
  while (reader.next(d) == ReadStatus::Ok)
    if (dst_port == 0 || d.dst_port == dst_port) out.push_back(d);
  if (error != nullptr) *error = reader.errorMessage();
  if (stats != nullptr) *stats = reader.stats();
  return out;
}

}  // namespace roadslam::pcap

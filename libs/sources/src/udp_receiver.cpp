#include "roadslam/sources/udp_receiver.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <stdexcept>
#include <vector>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"
#include "roadslam/velodyne/decoder_params.h"

namespace roadslam::sources {
namespace {

uint32_t parseIpv4(const std::string& text, const char* what) {
  if (text.empty()) return 0;
  in_addr a{};
  if (inet_pton(AF_INET, text.c_str(), &a) != 1)
    throw std::runtime_error(std::string("UdpReceiver: invalid IPv4 address for ") + what + ": '" +
                             text + "'");
  return ntohl(a.s_addr);
}

// Binds one socket; returns the fd and writes the port the kernel actually assigned.
int openSocket(uint32_t bind_ip, uint16_t port, int rcvbuf, int& granted, uint16_t& bound_port) {
  const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("UdpReceiver: socket(): ") + strerror(errno));
  const int one = 1;
  setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &one, sizeof one);
  setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof one);
  setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
  socklen_t len = sizeof granted;
  getsockopt(fd, SOL_SOCKET, SO_RCVBUF, &granted, &len);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(port);
  addr.sin_addr.s_addr = htonl(bind_ip);
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    const std::string err = strerror(errno);
    close(fd);
    throw std::runtime_error("UdpReceiver: cannot bind UDP port " + std::to_string(port) + ": " + err);
  }
  len = sizeof addr;
  getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  bound_port = ntohs(addr.sin_port);
  return fd;
}

}  // namespace

void UdpReceiver::Params::fields(ParamTable& t) {
  t.num("data_port", ports.data_port);
  t.num("position_port", ports.position_port);
  std::string model = velodyne::modelName(ports.model);  // parseModel also takes "VLP-16", ...
  t.text("model", model);
  if (t.loading()) {
    try {
      ports.model = velodyne::parseModel(model);
    } catch (const std::exception&) {
      throw std::runtime_error("[" + t.section() + "] model: expected auto, vlp16 or hdl32, got '" + model + "'");
    }
  }
  t.text("bind_address", bind_address);
  t.text("source_filter", source_filter);
  t.num("rcvbuf_bytes", rcvbuf_bytes);
  t.num("batch_size", batch_size);
  t.scaled("poll_timeout_ms", poll_timeout_s, unit::kMs);
  t.scaled("packet_period_us", packet_period_s, unit::kUs);
}

void UdpReceiver::Params::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                             const std::string& s) {
  loadFields(*this, cfg, s);
}

void UdpReceiver::Params::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                           const std::string& s) const {
  saveFields(*this, cfg, s);
}

UdpReceiver::UdpReceiver(const Params& p) : params_(p), gaps_(p.packet_period_s, p.ports.model) {
  const uint32_t bind_ip = parseIpv4(p.bind_address, "bind_address");
  source_ip_ = parseIpv4(p.source_filter, "source_filter");
  if (p.batch_size < 1) throw std::runtime_error("UdpReceiver: batch_size must be >= 1");
  batch_ = std::make_unique<Batch>(std::size_t(p.batch_size));
  fds_[0] = openSocket(bind_ip, p.ports.data_port, p.rcvbuf_bytes, granted_rcvbuf_, bound_data_port_);
  int granted_pos = 0;
  try {
    fds_[1] = openSocket(bind_ip, p.ports.position_port, p.rcvbuf_bytes, granted_pos,
                         bound_position_port_);
  } catch (...) {
    close(fds_[0]);
    throw;
  }
  params_.ports.data_port = bound_data_port_;
  params_.ports.position_port = bound_position_port_;
}

UdpReceiver::~UdpReceiver() {
  for (int fd : fds_)
    if (fd >= 0) close(fd);
}

std::string UdpReceiver::describe() const {
  const std::string a = params_.bind_address.empty() ? "0.0.0.0" : params_.bind_address;
  return "udp:" + a + ":" + std::to_string(bound_data_port_) + "+" +
         std::to_string(bound_position_port_);
}

// recvmmsg(2) batch: n datagram buffers with their control (cmsg) space and sender addresses.
struct UdpReceiver::Batch {
  static constexpr std::size_t kBuf = 2048;  // > 1206: oversize datagrams are counted, not cut
  static constexpr std::size_t kCtl =
      CMSG_SPACE(sizeof(timespec)) + CMSG_SPACE(sizeof(uint32_t)) + 64;
  explicit Batch(std::size_t n) : bufs(n * kBuf), ctl(n * kCtl), iov(n), msgs(n), from(n) {
    for (std::size_t i = 0; i < n; ++i) iov[i] = {bufs.data() + i * kBuf, kBuf};
  }
  // The kernel rewrites the lengths on every call.
  void reset() {
    for (std::size_t i = 0; i < msgs.size(); ++i) {
      msgs[i].msg_hdr = {};
      msgs[i].msg_hdr.msg_iov = &iov[i];
      msgs[i].msg_hdr.msg_iovlen = 1;
      msgs[i].msg_hdr.msg_control = ctl.data() + i * kCtl;
      msgs[i].msg_hdr.msg_controllen = kCtl;
      msgs[i].msg_hdr.msg_name = &from[i];
      msgs[i].msg_hdr.msg_namelen = sizeof(sockaddr_in);
    }
  }
  std::vector<uint8_t> bufs, ctl;
  std::vector<iovec> iov;
  std::vector<mmsghdr> msgs;
  std::vector<sockaddr_in> from;
};

void UdpReceiver::receiveBatch(int fd, uint16_t port, uint32_t& last_overflow) {
  Batch& b = *batch_;
  b.reset();
  const int got = recvmmsg(fd, b.msgs.data(), unsigned(b.msgs.size()), MSG_DONTWAIT, nullptr);
  for (int i = 0; i < got; ++i) {
    velodyne::RawPacket pkt;
    pkt.dst_port = port;
    pkt.src_ip = ntohl(b.from[i].sin_addr.s_addr);
    msghdr& h = b.msgs[i].msg_hdr;
    for (cmsghdr* c = CMSG_FIRSTHDR(&h); c; c = CMSG_NXTHDR(&h, c)) {
      if (c->cmsg_level != SOL_SOCKET) continue;
      if (c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec ts;
        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
        pkt.stamp_s = double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
      } else if (c->cmsg_type == SO_RXQ_OVFL) {
        uint32_t drops;  // cumulative count of the socket (socket(7))
        std::memcpy(&drops, CMSG_DATA(c), sizeof drops);
        stats_.kernel_drops += drops - last_overflow;
        last_overflow = drops;
      }
    }
    if (pkt.stamp_s == 0) {  // no kernel stamp (control space truncated): read the clock now
      timespec now;
      clock_gettime(CLOCK_REALTIME, &now);
      pkt.stamp_s = double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
    }
    if (source_ip_ != 0 && pkt.src_ip != source_ip_) {
      ++stats_.skipped_packets;
      continue;
    }
    const uint8_t* data = b.bufs.data() + std::size_t(i) * Batch::kBuf;
    pkt.payload.assign(data, data + b.msgs[i].msg_len);
    if (accountPacket(params_.ports, pkt, stats_, gaps_)) queue_.push_back(std::move(pkt));
  }
}

std::optional<velodyne::RawPacket> UdpReceiver::next() {
  if (queue_.empty()) {
    pollfd pfd[2] = {{fds_[0], POLLIN, 0}, {fds_[1], POLLIN, 0}};
    const int ms = int(params_.poll_timeout_s * 1e3);
    if (poll(pfd, 2, ms) > 0) {
      if (pfd[0].revents & POLLIN) receiveBatch(fds_[0], bound_data_port_, overflow_[0]);
      if (pfd[1].revents & POLLIN) receiveBatch(fds_[1], bound_position_port_, overflow_[1]);
      // Two sockets: merge their batches in kernel arrival order.
      std::stable_sort(queue_.begin(), queue_.end(),
                       [](const auto& a, const auto& b) { return a.stamp_s < b.stamp_s; });
    }
  }
  if (queue_.empty()) return std::nullopt;
  velodyne::RawPacket p = std::move(queue_.front());
  queue_.pop_front();
  return p;
}

}  // namespace roadslam::sources

// SocketCAN raw socket reader. Kernel interface: linux/can.h, linux/can/raw.h and
// Documentation/networking/can.rst (sections 4.1 RAW sockets, 4.1.5 CAN FD, SO_RXQ_OVFL in socket(7)).

#include <roadslam/can/socketcan_source.h>
#include <roadslam/common/config.h>
#include <roadslam/common/param_table.h>

#include <mrpt/config/CConfigFileBase.h>

#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace roadslam::can {
namespace {

std::int64_t nowMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string errnoText(int e) { return std::string(std::strerror(e)) + " (errno " + std::to_string(e) + ")"; }

// Converts the kernel's can_frame/canfd_frame (same header layout) into CanFrame.
bool fromKernel(const canfd_frame& k, std::size_t bytes, CanFrame& f) {
  f.flags = 0;
  if (bytes == CANFD_MTU) {
    f.flags |= kFd;
    f.fd_flags = k.flags & (CANFD_BRS | CANFD_ESI);
    if (k.len > CANFD_MAX_DLEN) return false;
  } else if (bytes == CAN_MTU) {
    const auto* c = reinterpret_cast<const can_frame*>(&k);
    if (c->len > CAN_MAX_DLEN) return false;
    f.len8_dlc = (c->len == CAN_MAX_DLEN && c->len8_dlc > CAN_MAX_DLEN) ? c->len8_dlc : 0;
  } else {
    return false;
  }
  if (k.can_id & CAN_ERR_FLAG) {
    f.flags |= kError;
    f.id = k.can_id & CAN_ERR_MASK;
  } else if (k.can_id & CAN_EFF_FLAG) {
    f.flags |= kExtended;
    f.id = k.can_id & CAN_EFF_MASK;
  } else {
    f.id = k.can_id & CAN_SFF_MASK;
  }
  if (k.can_id & CAN_RTR_FLAG) f.flags |= kRemote;
  f.len = k.len;
  f.data.fill(0);
  if (!(f.flags & kRemote)) std::memcpy(f.data.data(), k.data, f.len);
  return true;
}

// Kernel receive time (SO_TIMESTAMP) and the socket's cumulative drop counter (SO_RXQ_OVFL).
void readControl(msghdr& msg, std::int64_t& t_us, std::uint32_t& ovfl) {
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c)) {
    if (c->cmsg_level != SOL_SOCKET) continue;
    if (c->cmsg_type == SO_TIMESTAMP) {
      timeval tv{};
      std::memcpy(&tv, CMSG_DATA(c), sizeof(tv));
      t_us = static_cast<std::int64_t>(tv.tv_sec) * 1000000 + tv.tv_usec;
    } else if (c->cmsg_type == SO_RXQ_OVFL) {
      std::memcpy(&ovfl, CMSG_DATA(c), sizeof(ovfl));
    }
  }
}

}  // namespace

std::vector<CanFilter> parseFilters(const std::string& text) {
  std::vector<CanFilter> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item.empty()) continue;
    CanFilter f;
    std::string s = item;
    if (s[0] == '~') {
      f.invert = true;
      s = s.substr(1);
    }
    const std::size_t colon = s.find(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == s.size()) {
      throw std::invalid_argument("CAN filter '" + item + "' must be <id>:<mask> in hex");
    }
    try {
      std::size_t used = 0;
      f.id = static_cast<std::uint32_t>(std::stoul(s.substr(0, colon), &used, 16));
      if (used != colon) throw std::invalid_argument("id");
      f.mask = static_cast<std::uint32_t>(std::stoul(s.substr(colon + 1), &used, 16));
      if (used != s.size() - colon - 1) throw std::invalid_argument("mask");
    } catch (const std::exception&) {
      throw std::invalid_argument("CAN filter '" + item + "' must be <id>:<mask> in hex");
    }
    f.extended = colon == 8;
    out.push_back(f);
  }
  return out;
}

void SocketCanParams::fields(ParamTable& t) {
  t.text("interface", interface);
  std::ostringstream f;  // the filter list as text: "123:7FF,~12345678:1FFFFFFF"
  for (std::size_t i = 0; i < filters.size(); ++i) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), filters[i].extended ? "%s%08X:%X" : "%s%03X:%X", filters[i].invert ? "~" : "",
                  filters[i].id, filters[i].mask);
    f << (i ? "," : "") << buf;
  }
  std::string text = f.str();
  t.text("filters", text);
  if (t.loading()) {
    try {
      filters = parseFilters(text);
    } catch (const std::exception& e) {
      throw std::runtime_error("[" + t.section() + "] filters: " + e.what());
    }
  }
  t.flag("error_frames", error_frames);
  t.flag("fd", fd);
  t.num("receive_buffer_bytes", receive_buffer_bytes);
  t.num("reopen_interval_ms", reopen_interval_ms);
}

void SocketCanParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
}

void SocketCanParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

SocketCanSource::SocketCanSource(const SocketCanParams& params) : params_(params), owned_by_params_(true) {
  open();
}

SocketCanSource SocketCanSource::fromFd(int fd, const std::string& interface_name) {
  SocketCanSource s;
  s.fd_ = fd;
  const int one = 1;  // AF_UNIX datagram sockets also stamp on receive; failures just mean host stamps
  (void)::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof(one));
  (void)::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof(one));
  s.params_.interface = interface_name;
  return s;
}

SocketCanSource::SocketCanSource(SocketCanSource&& o) noexcept
    : params_(std::move(o.params_)),
      fd_(o.fd_),
      owned_by_params_(o.owned_by_params_),
      next_reopen_us_(o.next_reopen_us_),
      last_ovfl_(o.last_ovfl_),
      stats_(o.stats_) {
  o.fd_ = -1;
}

SocketCanSource::~SocketCanSource() {
  if (fd_ >= 0) ::close(fd_);
}

void SocketCanSource::open() {
  const std::string& ifc = params_.interface;
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) {
    throw std::runtime_error("SocketCAN '" + ifc + "': socket(PF_CAN) failed: " + errnoText(errno) +
                             (errno == EAFNOSUPPORT ? " - this kernel has no CAN support" : ""));
  }
  auto fail = [&](const std::string& what) {
    const int e = errno;
    ::close(fd);
    throw std::runtime_error("SocketCAN '" + ifc + "': " + what + ": " + errnoText(e));
  };
  const int one = 1;
  if (params_.fd && ::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &one, sizeof(one)) < 0) fail("CAN_RAW_FD_FRAMES");
  if (!params_.filters.empty()) {
    std::vector<can_filter> kf;
    for (const CanFilter& f : params_.filters) {
      can_filter k{};
      k.can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0) | (f.invert ? CAN_INV_FILTER : 0);
      k.can_mask = f.mask | CAN_EFF_FLAG;  // the EFF bit must match too: 11-bit vs 29-bit ids
      kf.push_back(k);
    }
    if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, kf.data(), static_cast<socklen_t>(kf.size() * sizeof(can_filter))) < 0) {
      fail("CAN_RAW_FILTER");
    }
  }
  if (params_.error_frames) {
    const can_err_mask_t em = CAN_ERR_MASK;
    if (::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &em, sizeof(em)) < 0) fail("CAN_RAW_ERR_FILTER");
  }
  if (::setsockopt(fd, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof(one)) < 0) fail("SO_TIMESTAMP");
  if (::setsockopt(fd, SOL_SOCKET, SO_RXQ_OVFL, &one, sizeof(one)) < 0) fail("SO_RXQ_OVFL");
  if (params_.receive_buffer_bytes > 0 &&
      ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &params_.receive_buffer_bytes, sizeof(int)) < 0) {
    fail("SO_RCVBUF");
  }
  sockaddr_can addr{};
  addr.can_family = AF_CAN;
  if (ifc != "any") {
    addr.can_ifindex = static_cast<int>(if_nametoindex(ifc.c_str()));
    if (addr.can_ifindex == 0) fail("no such interface");
  }
  if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) < 0) fail("bind");
  fd_ = fd;
}

bool SocketCanSource::reopenIfDue() {
  const std::int64_t now = nowMicros();
  if (now < next_reopen_us_) return false;
  next_reopen_us_ = now + static_cast<std::int64_t>(params_.reopen_interval_ms) * 1000;
  try {
    open();
    ++stats_.reopens;
    return true;
  } catch (const std::runtime_error&) {
    return false;  // still down: retried after reopen_interval_ms
  }
}

ReadStatus SocketCanSource::read(CanFrame& frame, int timeout_ms) {
  if (fd_ < 0) {
    if (!owned_by_params_) return ReadStatus::kEnd;
    if (!reopenIfDue()) {
      ::poll(nullptr, 0, timeout_ms < 0 ? params_.reopen_interval_ms : std::min(timeout_ms, params_.reopen_interval_ms));
      return ReadStatus::kTimeout;
    }
  }
  pollfd pfd{fd_, POLLIN, 0};
  const int pr = ::poll(&pfd, 1, timeout_ms);
  if (pr == 0 || (pr < 0 && errno == EINTR)) return ReadStatus::kTimeout;
  canfd_frame k{};
  sockaddr_can addr{};
  iovec iov{&k, sizeof(k)};
  alignas(cmsghdr) char ctrl[CMSG_SPACE(sizeof(timeval)) + CMSG_SPACE(sizeof(std::uint32_t)) + 64];
  msghdr msg{};
  msg.msg_name = &addr;
  msg.msg_namelen = sizeof(addr);
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = ctrl;
  msg.msg_controllen = sizeof(ctrl);
  const ssize_t n = ::recvmsg(fd_, &msg, MSG_DONTWAIT);
  if (n == 0 && !owned_by_params_) return ReadStatus::kEnd;  // peer closed (socketpair backend)
  if (n < 0) {
    if (errno == EAGAIN || errno == EINTR) return ReadStatus::kTimeout;
    if (owned_by_params_ && (errno == ENETDOWN || errno == ENODEV || errno == ENXIO)) {
      ::close(fd_);  // interface went down: reopen later, keep the run alive
      fd_ = -1;
      next_reopen_us_ = nowMicros() + static_cast<std::int64_t>(params_.reopen_interval_ms) * 1000;
      return ReadStatus::kTimeout;
    }
    if (!owned_by_params_) return ReadStatus::kEnd;
    ++stats_.malformed;
    return ReadStatus::kTimeout;
  }
  std::int64_t t_us = -1;
  std::uint32_t ovfl = last_ovfl_;
  readControl(msg, t_us, ovfl);
  stats_.dropped += ovfl - last_ovfl_;  // cumulative counter of the socket, wraps modulo 2^32
  last_ovfl_ = ovfl;
  if (!fromKernel(k, static_cast<std::size_t>(n), frame)) {
    ++stats_.malformed;
    return ReadStatus::kTimeout;
  }
  frame.t_us = t_us >= 0 ? t_us : nowMicros();  // no kernel stamp on non-CAN sockets: host clock
  char name[IF_NAMESIZE] = {0};
  if (msg.msg_namelen >= sizeof(addr) && addr.can_family == AF_CAN && addr.can_ifindex > 0 &&
      if_indextoname(static_cast<unsigned>(addr.can_ifindex), name)) {
    frame.setInterface(name);
  } else {
    frame.setInterface(params_.interface.c_str());
  }
  ++stats_.frames;
  if (frame.error()) ++stats_.error_frames;
  return ReadStatus::kFrame;
}

}  // namespace roadslam::can

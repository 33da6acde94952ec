#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <stdexcept>
#include <thread>

#include "roadslam/sim/outputs.h"
#include "roadslam/velodyne/packet.h"

namespace roadslam::sim {

namespace {
double wallNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

UdpStreamer::UdpStreamer(const std::string& host, uint16_t port, double speed) : speed_(speed) {
  static_assert(sizeof(sockaddr_in) <= sizeof(addr_));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  if (speed <= 0) throw std::runtime_error("UDP speed must be > 0");
  if (inet_pton(AF_INET, host.c_str(), &a.sin_addr) != 1)
    throw std::runtime_error("UDP host '" + host + "' is not an IPv4 address");
  fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (fd_ < 0) throw std::runtime_error("cannot create a UDP socket for " + host);
  std::memcpy(addr_, &a, sizeof(a));
}

UdpStreamer::~UdpStreamer() {
  if (fd_ >= 0) ::close(fd_);
}

void UdpStreamer::packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) {
  if (port != velodyne::kDefaultDataPort) return;
  if (first_capture_ < 0) {
    first_capture_ = capture_s;
    wall0_ = wallNow();
  }
  const double due = wall0_ + (capture_s - first_capture_) / speed_;
  const double now = wallNow();
  if (due > now) std::this_thread::sleep_for(std::chrono::duration<double>(due - now));
  else if (now - due > 0.01) ++late_;
  // A full socket buffer or an unreachable port is a per-packet problem: counted, never fatal.
  if (::sendto(fd_, data, size, 0, reinterpret_cast<const sockaddr*>(addr_), sizeof(sockaddr_in)) ==
      static_cast<ssize_t>(size))
    ++sent_;
}

}  // namespace roadslam::sim

#pragma once
/// \file frame.h
/// One CAN / CAN FD frame as received from a bus or read from a candump log. Plain value type, no
/// allocation, so the per-frame path (socket read, log parse, decode) never touches the heap.

#include <array>
#include <cstdint>
#include <cstring>

namespace roadslam::can {

/// Frame flags (bit set in CanFrame::flags).
enum FrameFlag : std::uint8_t {
  kExtended = 0x01,  ///< 29-bit identifier (CAN_EFF_FLAG)
  kRemote = 0x02,    ///< remote transmission request (CAN_RTR_FLAG), no payload
  kError = 0x04,     ///< error frame (CAN_ERR_FLAG); id holds the error class bits
  kFd = 0x08,        ///< CAN FD frame (payload up to 64 bytes)
};

/// CAN FD per-frame flags as in linux/can.h canfd_frame::flags (the candump `##<nibble>`).
enum FdFlag : std::uint8_t { kFdBrs = 0x01, kFdEsi = 0x02 };

constexpr std::size_t kMaxInterfaceName = 16;  ///< IFNAMSIZ in Linux, including the terminating 0

struct CanFrame {
  std::int64_t t_us = 0;       ///< receive time [us since Unix epoch] (candump's resolution)
  std::uint32_t id = 0;        ///< identifier without flags: 11 bit, or 29 bit when kExtended
  std::uint8_t len = 0;        ///< payload length [bytes], 0..8 classic, 0..64 FD
  std::uint8_t flags = 0;      ///< FrameFlag bits
  std::uint8_t fd_flags = 0;   ///< FdFlag bits (FD frames only)
  std::uint8_t len8_dlc = 0;   ///< classic CAN raw DLC 9..15 when len == 8 (0 = not used)
  std::array<char, kMaxInterfaceName> iface{};  ///< interface name ("can0"), 0-terminated
  std::array<std::uint8_t, 64> data{};          ///< payload, bytes past len are zero

  bool extended() const noexcept { return (flags & kExtended) != 0; }
  bool remote() const noexcept { return (flags & kRemote) != 0; }
  bool error() const noexcept { return (flags & kError) != 0; }
  bool fd() const noexcept { return (flags & kFd) != 0; }
  double timeSeconds() const noexcept { return static_cast<double>(t_us) * 1e-6; }
  /// Copies \p name (cut to 15 characters) into iface.
  void setInterface(const char* name) noexcept;
};

bool operator==(const CanFrame& a, const CanFrame& b) noexcept;
inline bool operator!=(const CanFrame& a, const CanFrame& b) noexcept { return !(a == b); }

/// CAN FD DLC (0..15) to payload length (ISO 11898-1:2015 table 5).
std::uint8_t fdDlcToLen(std::uint8_t dlc) noexcept;
/// Payload length to the smallest CAN FD length that can carry it (0..64), as the kernel pads.
std::uint8_t fdPaddedLen(std::uint8_t len) noexcept;

}  // namespace roadslam::can

#pragma once
/// \file socketcan_source.h
/// Live frames from a Linux SocketCAN raw socket (Documentation/networking/can.rst): id/mask
/// filters, error frames, kernel receive timestamps (SO_TIMESTAMP), CAN FD (CAN_RAW_FD_FRAMES), the
/// kernel drop counter (SO_RXQ_OVFL), and reopening when the interface goes down and up.
/// The read loop also runs on any datagram socket carrying struct can_frame / canfd_frame, e.g. one
/// end of socketpair(AF_UNIX, SOCK_SEQPACKET): that is how it is tested where the kernel has no CAN.

#include <roadslam/can/frame_source.h>

#include <cstdint>
#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::can {

/// Receive filter: a frame passes when (id & mask) == (filter id & mask) (CAN_RAW_FILTER).
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool extended = false;  ///< match 29-bit frames (else 11-bit)
  bool invert = false;    ///< CAN_INV_FILTER: pass what does not match
};

struct SocketCanParams {
  std::string interface = "can0";  ///< interface name; "any" = every CAN interface
  std::vector<CanFilter> filters;  ///< empty = all frames
  bool error_frames = true;        ///< also receive error frames (CAN_RAW_ERR_FILTER = all classes)
  bool fd = true;                  ///< receive CAN FD frames (CAN_RAW_FD_FRAMES)
  int receive_buffer_bytes = 0;    ///< SO_RCVBUF, 0 = kernel default [bytes]
  int reopen_interval_ms = 1000;   ///< retry period while the interface is down [ms]

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Keys: interface, filters ("id:mask" hex, comma separated, "~" prefix inverts, 8-digit ids
  /// are 29-bit), error_frames, fd, receive_buffer_bytes, reopen_interval_ms.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// Parses "123:7FF,~12345678:1FFFFFFF"; throws std::invalid_argument naming the bad item.
std::vector<CanFilter> parseFilters(const std::string& text);

class SocketCanSource : public FrameSource {
 public:
  /// Opens and binds a raw CAN socket; throws std::runtime_error naming the interface and errno
  /// (EAFNOSUPPORT: no CAN in this kernel; ENODEV: no such interface).
  explicit SocketCanSource(const SocketCanParams& params);
  /// Reads from an already open datagram socket carrying can_frame/canfd_frame (takes ownership);
  /// frames are labelled \p interface_name. No reopen on errors.
  static SocketCanSource fromFd(int fd, const std::string& interface_name);
  ~SocketCanSource() override;
  SocketCanSource(SocketCanSource&& o) noexcept;
  SocketCanSource(const SocketCanSource&) = delete;
  SocketCanSource& operator=(const SocketCanSource&) = delete;
  SocketCanSource& operator=(SocketCanSource&&) = delete;

  ReadStatus read(CanFrame& frame, int timeout_ms) override;
  const SourceStats& stats() const override { return stats_; }

 private:
  SocketCanSource() = default;
  void open();
  bool reopenIfDue();
  SocketCanParams params_;
  int fd_ = -1;
  bool owned_by_params_ = false;  ///< opened from params (can reopen) vs fromFd
  std::int64_t next_reopen_us_ = 0;
  std::uint32_t last_ovfl_ = 0;
  SourceStats stats_;
};

}  // namespace roadslam::can

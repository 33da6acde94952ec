#pragma once
/// \file udp_receiver.h
/// Live Velodyne receiver (Linux): one UDP socket on the data port (2368) and one on the position
/// port (8308), read in batches with recvmmsg(2), stamped by the kernel at reception
/// (SO_TIMESTAMPNS), kernel drops counted through SO_RXQ_OVFL. Written because MRPT's
/// CVelodyneScanner polls with 1 ms timeouts, binds without SO_REUSEADDR and lost 38 % of the
/// packets at 1,508 packets/s here (MRPT-NOTES.md).

#include <deque>
#include <memory>
#include <string>

#include "roadslam/sources/packet_source.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::sources {

class UdpReceiver : public PacketSource {
 public:
  struct Params {
    PortConfig ports;              ///< data / position ports [UDP port]; 0 = let the kernel pick
    std::string bind_address;      ///< local IPv4 address to bind, empty = all interfaces
    std::string source_filter;     ///< accept only datagrams from this IPv4 sender, empty = any
    int rcvbuf_bytes = 8 << 20;    ///< requested SO_RCVBUF [bytes]; the kernel may grant less
    int batch_size = 64;           ///< datagrams per recvmmsg call [count]
    double poll_timeout_s = 0.1;   ///< next() returns nullopt after this long without data [s]
    double packet_period_s = 0;    ///< expected data packet step for gap counting [s], 0 = from mode

    /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
    void fields(ParamTable& t);
    /// Keys: data_port, position_port, model (auto|vlp16|hdl32), bind_address, source_filter, rcvbuf_bytes, batch_size,
    /// poll_timeout_ms (converted to s), packet_period_us (converted to s).
    void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
    void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
  };

  /// Opens and binds both sockets; throws std::runtime_error naming the address/port on failure.
  explicit UdpReceiver(const Params& params);
  ~UdpReceiver() override;
  UdpReceiver(const UdpReceiver&) = delete;
  UdpReceiver& operator=(const UdpReceiver&) = delete;

  /// Next packet stamped with the kernel receive time [s since epoch]; nullopt after
  /// poll_timeout_s without traffic. In arrival order per port, and across the two ports within
  /// each batch.
  std::optional<velodyne::RawPacket> next() override;
  bool finished() const override { return false; }
  const SourceStats& stats() const override { return stats_; }
  std::string describe() const override;

  uint16_t dataPort() const { return bound_data_port_; }          ///< actually bound [UDP port]
  uint16_t positionPort() const { return bound_position_port_; }  ///< actually bound [UDP port]
  /// SO_RCVBUF the kernel granted (Linux reports twice the usable size) [bytes].
  int grantedRcvbufBytes() const { return granted_rcvbuf_; }

 private:
  void receiveBatch(int fd, uint16_t port, uint32_t& last_overflow);

  struct Batch;  // recvmmsg buffers, allocated once
  std::unique_ptr<Batch> batch_;
  Params params_;
  int fds_[2] = {-1, -1};
  uint16_t bound_data_port_ = 0, bound_position_port_ = 0;
  uint32_t source_ip_ = 0;  // host byte order, 0 = any
  int granted_rcvbuf_ = 0;
  uint32_t overflow_[2] = {0, 0};
  std::deque<velodyne::RawPacket> queue_;
  SourceStats stats_;
  GapCounter gaps_;
};

}  // namespace roadslam::sources

#pragma once
/// \file packet_source.h
/// One interface for every origin of raw Velodyne UDP payloads (live UDP, pcap capture, MRPT
/// rawlog): downstream code (SweepSource, the rawlog writer, the apps) never knows whether data is
/// live or recorded (STYLE.md rule 3, MOLA's input modules).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roadslam/sources/gps_fix.h"
#include "roadslam/velodyne/layout.h"
#include "roadslam/velodyne/packet.h"

namespace roadslam::sources {

/// Counters every backend keeps; problems in the per-packet path are counted here, never thrown.
struct SourceStats {
  uint64_t packets = 0;            ///< payloads returned by next() [count]
  uint64_t data_packets = 0;       ///< 1206-byte payloads on the data port [count]
  uint64_t position_packets = 0;   ///< 512-byte payloads on the position port (or GPS records) [count]
  uint64_t malformed_packets = 0;  ///< on a Velodyne port with the wrong size [count], not returned
  uint64_t skipped_packets = 0;    ///< non-UDP / other-port / filtered traffic [count], not returned
  uint64_t missing_packets = 0;    ///< gaps in the sensor's packet timestamps (see GapCounter) [count]
  uint64_t kernel_drops = 0;       ///< datagrams dropped by a full socket buffer (SO_RXQ_OVFL) [count]
  double first_stamp_s = 0;        ///< stamp of the first returned packet [s]
  double last_stamp_s = 0;         ///< stamp of the last returned packet [s]
};

/// How far a recording has been read, for progress and ETA: bytes of its file(s) [bytes]; total 0 =
/// unknown (live). Compressed files count their compressed bytes.
struct ReadProgress {
  uint64_t bytes_read = 0;
  uint64_t bytes_total = 0;
};

/// Ports that identify Velodyne traffic (VLP-16 manual 63-9243, section 9).
struct PortConfig {
  uint16_t data_port = velodyne::kDefaultDataPort;          ///< [UDP port]
  uint16_t position_port = velodyne::kDefaultPositionPort;  ///< [UDP port]
  /// Sensor model for the missing-packet count; Unknown = the packet's product byte. Force it for
  /// captures whose byte lies (early VLP-16 firmware reports 0x21, the HDL-32E code).
  velodyne::Model model = velodyne::Model::Unknown;
};

/// A stream of raw UDP payloads, in arrival order.
class PacketSource {
 public:
  virtual ~PacketSource() = default;
  /// The next valid data or position packet. std::nullopt: end of a recording, or (live) nothing
  /// arrived within the backend's poll timeout; tell them apart with finished().
  virtual std::optional<velodyne::RawPacket> next() = 0;
  /// True once a recording is exhausted (a live source never finishes).
  virtual bool finished() const = 0;
  virtual const SourceStats& stats() const = 0;
  /// Short human-readable origin, e.g. "pcap:/path/file.pcap" or "udp:0.0.0.0:2368".
  virtual std::string describe() const = 0;
  /// Non-empty when the recording turned out damaged (truncated, undecodable record): names the
  /// file and the place. The packets before the damage were returned normally.
  virtual std::string errorMessage() const { return {}; }
  /// GPS fixes the source holds already decoded (rawlog CObservationGPS records) since the last
  /// call; position packets returned by next() are not repeated here.
  virtual std::vector<gnss::GnssFix> takeDecodedFixes() { return {}; }
  /// Bytes of the recording read so far and in all (both 0 for a live source).
  virtual ReadProgress readProgress() const { return {}; }
};

/// Counts packets missing from a data stream from the sensor's own timestamps (bytes 1200-1203, us
/// past the hour): a step larger than 1.5 expected periods means round(step/period)-1 packets lost.
/// Period (unless \p forced_period_s > 0): VLP-16 1327.104 us (24 sequences x 55.296 us), HDL-32E
/// 552.96 us (12 blocks x 46.08 us); half of it in dual return mode (each firing fills two blocks).
/// The model is \p model or, when Unknown, the one velodyne::chooseModel gives for the stream's first
/// LayoutDetector::kWindowPackets packets (their layout over a disagreeing product byte; the packet's
/// own byte when neither names a model): the steps of that window are counted once it is chosen.
class GapCounter {
 public:
  explicit GapCounter(double forced_period_s = 0, velodyne::Model model = velodyne::Model::Unknown)
      : forced_period_s_(forced_period_s), model_(model) {}
  /// Expected step between consecutive data packets [s].
  static double packetPeriod_s(velodyne::Model model, bool dual);
  /// Feeds one 1206-byte data payload; returns the packets missing just before it [count] (0 while
  /// the model is being chosen: those steps are counted when it is).
  uint64_t feed(const uint8_t* payload);
  /// Packets missing so far [count], the steps of a window still open counted with the model its
  /// packets show so far.
  uint64_t missing() const;

 private:
  struct Step {
    int64_t step_us;
    bool dual;
    uint8_t product;
  };
  uint64_t lost(const Step& s, velodyne::Model model) const;
  velodyne::Model streamModel() const;

  double forced_period_s_;
  velodyne::Model model_;
  int64_t last_us_ = -1;
  uint64_t missing_ = 0;
  velodyne::LayoutDetector layout_;
  std::vector<Step> pending_;  // steps of the layout window, counted once the model is chosen
  bool chosen_ = false;
  velodyne::Model chosen_model_ = velodyne::Model::Unknown;
};

/// Classification of one UDP payload by port and size, shared by every backend.
enum class PacketKind { Data, Position, Malformed, Other };
PacketKind classify(const PortConfig& ports, uint16_t dst_port, std::size_t size);

/// Applies classify() and updates \p stats (and \p gaps for data packets); returns true when the
/// packet is to be passed on to the caller.
bool accountPacket(const PortConfig& ports, const velodyne::RawPacket& pkt, SourceStats& stats,
                   GapCounter& gaps);

}  // namespace roadslam::sources

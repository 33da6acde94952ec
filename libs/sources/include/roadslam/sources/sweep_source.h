#pragma once
/// \file sweep_source.h
/// Turns any PacketSource (live UDP, pcap, rawlog) into decoded sweeps (roadslam::Scan, lidar
/// frame, see libs/velodyne decoder.h) and GPS fixes, through libs/velodyne's SweepAssembler.
/// The first sweep of a stream and the one closed at its end are flagged Scan::partial.

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/sources/gps_fix.h"
#include "roadslam/sources/packet_source.h"
#include "roadslam/sources/scan_source.h"
#include "roadslam/velodyne/model_choice.h"
#include "roadslam/velodyne/sweep_assembler.h"

namespace roadslam::sources {

struct SweepSourceStats {
  uint64_t sweeps = 0;           ///< sweeps returned (partial included) [count]
  uint64_t partial_sweeps = 0;   ///< of which partial [count]
  uint64_t points = 0;           ///< points in returned sweeps [count]
  uint64_t gps_fixes = 0;        ///< fixes handed out by takeGpsFixes() [count]
  uint64_t gps_fixes_dropped = 0;  ///< oldest fixes dropped beyond setMaxPendingGpsFixes() [count]
  uint64_t undecodable_packets = 0;  ///< data packets the decoder rejected (bad flag, model) [count]
  double first_wrap_stamp_s = 0; ///< Scan::stamp_s of the first sweep that began at a wrap [s]
  double last_wrap_stamp_s = 0;  ///< ... and of the last one [s]
  uint64_t wrap_sweeps = 0;      ///< sweeps that began at a wrap (all but the stream's first) [count]
  /// Rotation rate from the wrap-to-wrap stamps [1/s]; 0 with fewer than two wraps.
  double sweepRate_hz() const;
};

/// Before the first sweep, the source reads the first velodyne::LayoutDetector::kWindowPackets data
/// packets ahead (with the position packets between them) and chooses the stream's model from their
/// layout and product byte (velodyne/model_choice.h); then it decodes every packet, those read ahead
/// first, in arrival order, with that model. lidarModel() tells the choice, warnings() its warning.
class SweepSource : public ScanSource {
 public:
  /// \p packets is owned; \p params select model, calibration, cut angle, stamp clock.
  /// \p force_setting names how a user forces the model, for the warning's advice (model_choice.h).
  SweepSource(std::unique_ptr<PacketSource> packets, const velodyne::DecoderParams& params = {},
              std::string force_setting = "[velodyne] model");

  /// Next sweep; nullopt when the recording is exhausted (after the final partial sweep) or, live,
  /// when no packet arrived within the receiver's timeout.
  std::optional<Scan> next() override;
  bool finished() const override { return finished_ && !assembler_.hasSweep(); }
  /// GPS fixes received since the last call, in arrival order.
  std::vector<gnss::GnssFix> takeGpsFixes() override;
  /// Keep at most \p n untaken fixes, the newest (0 = all, the default). For consumers that never
  /// take them: a VLP-16 sends about 150 position packets a second, so an hour's drive would pile
  /// up half a million. openScanSource() sets kMaxPendingGpsFixes.
  void setMaxPendingGpsFixes(std::size_t n) { max_pending_fixes_ = n; }
  static constexpr std::size_t kMaxPendingGpsFixes = 4096;
  /// The packet source's origin, e.g. "pcap:/path/file.pcap" (what the jobs' summaries show as input).
  std::string describe() const override { return packets_->describe(); }
  /// Sweeps closed by the assembler, packets read, and malformed packets: the source's plus the
  /// decoder's rejections (see sweepStats() for the sweeps handed out and the GPS fixes).
  ScanSourceStats stats() const override;
  /// The packet source's damage report (truncated or undecodable recording), empty when none.
  std::string errorMessage() const override { return packets_->errorMessage(); }
  /// The model choice's warning (layout against product byte or set model), when there is one.
  std::vector<std::string> warnings() const override;
  /// The model chosen (model_choice.h); before the first next() the choice is not made yet and the
  /// model reads "undecided".
  std::optional<LidarModelReport> lidarModel() const override;
  ReadProgress readProgress() const override { return packets_->readProgress(); }
  /// The choice itself; nullopt before the first next().
  const std::optional<velodyne::ModelChoice>& modelChoice() const { return choice_; }
  /// The sweeps closed when the damage was first seen (a roadslam-grab session goes on with the next
  /// segment after a damaged one; a single file ends there, and this is all of them).
  uint64_t sweepsBeforeDamage() const override { return damage_seen_ ? sweeps_before_damage_ : stats().sweeps; }

  /// Optional observer of every raw packet (data and position) in arrival order, with the number
  /// of sweeps the assembler closed while taking it (data packets only): lets a recorder store the
  /// raw packets grouped like the decoded sweeps.
  using PacketObserver = std::function<void(const velodyne::RawPacket&, std::size_t closed)>;
  void setPacketObserver(PacketObserver obs) { observer_ = std::move(obs); }

  const PacketSource& packets() const { return *packets_; }
  const velodyne::SweepStats& assemblerStats() const { return assembler_.stats(); }
  const velodyne::Decoder& decoder() const { return assembler_.decoder(); }
  const SweepSourceStats& sweepStats() const { return stats_; }

 private:
  /// A packet read ahead for the model choice, with the fixes the source decoded beside it.
  struct ReadAhead {
    std::optional<velodyne::RawPacket> packet;
    std::vector<gnss::GnssFix> fixes;
  };
  Scan deliver(Scan s);
  void keepFix(const gnss::GnssFix& f);
  /// Reads ahead until the layout window is full or the recording ends, then chooses the model;
  /// false while a live source has not delivered the window yet.
  bool chooseModel();
  /// The next packet: read ahead first, then from the source (fixes kept); sets \p waiting when a
  /// live source had nothing.
  std::optional<velodyne::RawPacket> nextPacket(bool& waiting);

  std::unique_ptr<PacketSource> packets_;
  velodyne::DecoderParams params_;
  std::string force_setting_;
  velodyne::LayoutDetector layout_;
  std::deque<ReadAhead> ahead_;
  std::optional<velodyne::ModelChoice> choice_;
  velodyne::SweepAssembler assembler_;
  std::deque<gnss::GnssFix> fixes_;
  std::size_t max_pending_fixes_ = 0;
  PacketObserver observer_;
  SweepSourceStats stats_;
  bool finished_ = false;
  bool damage_seen_ = false;
  uint64_t sweeps_before_damage_ = 0;
};

}  // namespace roadslam::sources

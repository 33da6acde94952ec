#pragma once
/// \file vehicle_state.h
/// Turns CAN frames into a stream of VehicleState updates: the latest value of every quantity the
/// car reports, in SI units and ISO 8855 body axes (x forward, y left, z up, yaw CCW positive).
/// Consumers (dead reckoning, rawlog export, later the odometry prior) only see VehicleState.

#include <roadslam/can/candump.h>
#include <roadslam/can/decoder.h>
#include <roadslam/can/frame.h>
#include <roadslam/vehicle/params.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

namespace roadslam::vehicle {

/// Latest known vehicle quantities. value(q) is meaningful when has(q).
struct VehicleState {
  double t_s = 0;                        ///< time of the last update [s since Unix epoch]
  std::array<double, kQuantityCount> v{};  ///< SI values indexed by Quantity
  std::array<double, kQuantityCount> t{};  ///< time of each quantity's last update [s]
  std::uint32_t valid = 0;               ///< bit q set once quantity q was decoded

  bool has(Quantity q) const { return (valid >> static_cast<int>(q)) & 1U; }
  double value(Quantity q) const { return v[static_cast<std::size_t>(q)]; }
  /// Mean of the wheel speeds reported (all four, else vehicle speed) [m/s]; 0 if none.
  double speed() const;
  bool reverse = false;  ///< gear is one of VehicleParams::reverse_gear_values
};

/// Bit mask of the quantities updated by one frame.
using UpdateMask = std::uint32_t;
constexpr UpdateMask bit(Quantity q) { return 1U << static_cast<int>(q); }
constexpr UpdateMask kWheelMask =
    bit(Quantity::kWheelFL) | bit(Quantity::kWheelFR) | bit(Quantity::kWheelRL) | bit(Quantity::kWheelRR);

/// Counts of a decoding run, reported at the end.
struct VehicleDecodeStats {
  std::size_t frames = 0;          ///< frames seen
  std::size_t other_interface = 0; ///< skipped: not VehicleParams::interface
  std::size_t used = 0;            ///< frames that updated at least one quantity
  std::size_t short_frames = 0;    ///< relevant frames too short for a mapped signal
  std::size_t dlc_mismatch = 0;    ///< relevant frames whose length differs from the DBC
};

class VehicleDecoder {
 public:
  /// Loads the DBC (VehicleParams::dbcPath()) and plans the mapped signals; throws naming the DBC
  /// file or the first mapped signal missing from it.
  explicit VehicleDecoder(const VehicleParams& params);
  /// As above with a database already loaded.
  VehicleDecoder(const VehicleParams& params, can::Database db);
  ~VehicleDecoder();

  /// Updates \p state from one frame; returns the quantities updated (0 for irrelevant frames).
  UpdateMask process(const can::CanFrame& frame, VehicleState& state) noexcept;
  const VehicleDecodeStats& stats() const { return stats_; }
  const VehicleParams& params() const { return params_; }

 private:
  struct Slot;  // one mapped quantity: plan indices of its signals
  VehicleParams params_;
  std::unique_ptr<can::Decoder> decoder_;
  std::vector<Slot> slots_;
  std::vector<std::vector<std::size_t>> slots_of_plan_;  ///< plan index -> slots
  std::vector<double> scratch_;
  std::vector<double> reverse_values_;
  VehicleDecodeStats stats_;
};

/// A recorded drive's candump log (can/candump.h) replayed through a VehicleDecoder, frame by frame
/// in log order, up to a time: the one loop behind every consumer of a recorded CAN log that streams
/// it (roadslam-map's motion prior, the viewer's CAN samples).
class VehicleLogReader {
 public:
  /// Opens \p log with the car's \p params; throws naming the log or the DBC when either cannot be read.
  VehicleLogReader(const std::string& log, const VehicleParams& params);

  /// Reads on through the frames stamped at or before \p t_s [s since Unix epoch] (to the end with
  /// +infinity), calling \p on_frame(state, mask) after each (mask 0: the frame updated nothing). The
  /// first frame past \p t_s is kept for the next call. Returns the frames read.
  std::size_t readUntil(double t_s, const std::function<void(const VehicleState&, UpdateMask)>& on_frame);
  bool ended() const { return ended_; }
  const can::CandumpStats& logStats() const { return reader_.stats(); }
  const VehicleDecoder& decoder() const { return decoder_; }

 private:
  can::CandumpReader reader_;
  VehicleDecoder decoder_;
  VehicleState state_;
  can::CanFrame pending_;
  bool have_pending_ = false, ended_ = false;
};

}  // namespace roadslam::vehicle

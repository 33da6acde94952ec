#pragma once
/// \file sweep_sink.h
/// Simulated data packets decoded into sweeps by our own decoder (velodyne::SweepAssembler), each
/// handed on as it completes: what every consumer that scores against the simulator needs, without
/// writing a pcap first.

#include <functional>
#include <utility>

#include "roadslam/sim/simulator.h"
#include "roadslam/velodyne/sweep_assembler.h"

namespace roadslam::sim {

class SweepSink : public PacketSink {
 public:
  using OnSweep = std::function<void(Scan&&)>;
  explicit SweepSink(OnSweep on_sweep, const velodyne::DecoderParams& params = {})
      : assembler_(params), on_sweep_(std::move(on_sweep)) {}

  void packet(double capture_s, uint16_t port, const uint8_t* data, std::size_t size) override {
    if (port != velodyne::kDefaultDataPort) return;
    assembler_.addPacket(data, size, capture_s);
    while (assembler_.hasSweep()) on_sweep_(assembler_.takeSweep());
  }

 private:
  velodyne::SweepAssembler assembler_;
  OnSweep on_sweep_;
};

}  // namespace roadslam::sim

// libFuzzer target: any bytes as a data packet (decoder, sweep assembler) and as a position
// packet / NMEA sentence. Built with -fsanitize=fuzzer when ROADSLAM_FUZZ=ON (clang); also linked
// into the deterministic ctest driver (tests/test_fuzz_driver.cpp) for gcc CI.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/velodyne/decoder.h"
#include "roadslam/velodyne/position.h"
#include "roadslam/velodyne/sweep_assembler.h"

using namespace roadslam::velodyne;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  static const Decoder auto_model{};
  static const Decoder forced_hdl32 = [] {
    DecoderParams p;
    p.model = Model::HDL32;
    p.dual_returns = DualReturns::Both;
    return Decoder(p);
  }();
  static std::vector<roadslam::ScanPoint> out;
  out.clear();
  auto_model.decode(data, size, out);
  forced_hdl32.decode(data, size, out);
  if (out.size() > 2 * kBlocksPerPacket * kChannelsPerBlock) __builtin_trap();
  // The same bytes as a stream of 1206-byte packets through the assembler.
  SweepAssembler assembler(auto_model);
  for (std::size_t off = 0; off + kDataPacketSize <= size; off += kDataPacketSize)
    assembler.addPacket(data + off, kDataPacketSize, static_cast<double>(off));
  assembler.addPacket(data, size, 0.0);
  assembler.finish();
  while (assembler.hasSweep()) assembler.takeSweep();
  PositionPacket pp;
  decodePositionPacket(data, size, pp);
  roadslam::gnss::parseRmc(std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}

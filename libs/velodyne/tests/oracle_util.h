#pragma once
// Shared helpers of the oracle tests: locate the shared data and run a pcap through the assembler.
#include <fstream>
#include <string>
#include <vector>

#include "roadslam/pcap/pcap_reader.h"
#include "roadslam/velodyne/sweep_assembler.h"

namespace roadslam::velodyne::test {

inline std::string dataFile(const std::string& name) {
  return std::string(ROADSLAM_SHARED_DATA) + "/velodyne/" + name;
}
inline bool exists(const std::string& path) { return std::ifstream(path).good(); }

/// Every sweep of a capture's data packets (port 2368), in order, partial ones included.
inline std::vector<Scan> sweepsOf(const std::string& pcap, const DecoderParams& params,
                                  SweepStats* stats = nullptr) {
  SweepAssembler assembler(params);
  std::vector<Scan> sweeps;
  pcap::PcapReader reader(pcap);
  pcap::UdpDatagram d;
  while (reader.next(d) == pcap::ReadStatus::Ok) {
    if (d.dst_port != kDefaultDataPort) continue;
    assembler.addPacket(d.payload.data(), d.payload.size(), d.stamp_s);
    while (assembler.hasSweep()) sweeps.push_back(assembler.takeSweep());
  }
  assembler.finish();
  while (assembler.hasSweep()) sweeps.push_back(assembler.takeSweep());
  if (stats != nullptr) *stats = assembler.stats();
  return sweeps;
}

}  // namespace roadslam::velodyne::test

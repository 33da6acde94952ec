// libFuzzer target: any bytes as a capture file (libpcap + our link/IP/UDP parsing), and as one
// frame of every supported link type. Built with -fsanitize=fuzzer when ROADSLAM_FUZZ=ON (clang);
// also linked into the deterministic ctest driver (tests/test_fuzz_driver.cpp) for gcc CI.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "../src/link_layer.h"
#include "roadslam/pcap/pcap_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  using namespace roadslam::pcap;
  for (int dlt : {0, 1, 12, 113, 228, 276}) {
    const link::Parsed p = link::parseFrame(dlt, data, size, size);
    if (p.kind == link::Kind::Udp && (p.payload < data || p.payload + p.payload_size > data + size))
      __builtin_trap();  // the payload must lie inside the frame
  }
  static const std::string path = "/tmp/roadslam_fuzz_pcap_" + std::to_string(::getpid()) + ".pcap";
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) return 0;
  if (size > 0) std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    PcapReader reader(path);
    UdpDatagram d;
    while (reader.next(d) == ReadStatus::Ok) {
    }
  } catch (const std::runtime_error&) {
    // Rejected at open: expected for most inputs.
  }
  std::remove(path.c_str());
  return 0;
}

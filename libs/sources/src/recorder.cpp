#include "roadslam/sources/recorder.h"

#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/stop_signal.h"
#include "roadslam/pcap/pcap_writer.h"

namespace roadslam::sources {

RecordSummary recordToPcap(PacketSource& src, const std::string& out, const RecordLimits& limits) {
  const std::string tmp = tempPathFor(out);
  RecordSummary sum;
  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed_s = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  try {
    pcap::PcapWriter writer(tmp, out);
    while (!stopRequested() && !src.finished()) {
      if (limits.duration_s > 0 && elapsed_s() >= limits.duration_s) break;
      if (limits.max_packets > 0 && sum.packets >= limits.max_packets) break;
      auto p = src.next();
      if (!p) continue;  // live: poll timeout, re-check the limits
      // Recorded on the standard ports of the packet's role (the source already classified it
      // by port and size), whatever port the receiver listened on: the capture then replays in
      // every Velodyne tool. Sensors send from the port they send to (2368 -> 2368).
      const uint16_t port = p->payload.size() == velodyne::kPositionPacketSize
                                ? velodyne::kDefaultPositionPort
                                : velodyne::kDefaultDataPort;
      writer.writeUdp(p->stamp_s, port, port, p->payload.data(), p->payload.size(), p->src_ip);
      ++sum.packets;
    }
    writer.close();
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    const std::string what = e.what();
    throw std::runtime_error(what.find(out) != std::string::npos ? what
                                                                  : out + ": " + what);
  }
  sum.source = src.stats();
  if (sum.packets == 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(out + ": not written, no Velodyne packets received from " +
                             src.describe());
  }
  commitTempFile(tmp, out);
  return sum;
}

}  // namespace roadslam::sources

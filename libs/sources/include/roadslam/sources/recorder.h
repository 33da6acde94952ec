#pragma once
/// \file recorder.h
/// Records any PacketSource (typically the live UdpReceiver) into a libpcap capture, the replay
/// format of every other tool here (`roadslam-rawlog info/convert`, VeloView, Wireshark):
/// what is recorded is exactly what is replayed, kernel receive stamps and sender address
/// included. Packets are written on the standard ports of their role (data 2368, position 8308)
/// even when the receiver listened on others.

#include <cstdint>
#include <string>

#include "roadslam/sources/packet_source.h"

namespace roadslam::sources {

struct RecordLimits {
  double duration_s = 0;     ///< stop after this long [s]; 0 = no limit
  uint64_t max_packets = 0;  ///< stop after this many packets (data + position) [count]; 0 = none
};

struct RecordSummary {
  uint64_t packets = 0;       ///< packets written (data + position) [count]
  SourceStats source;         ///< the source's counters at the end (drops, malformed, missing)
};

/// Copies packets from \p src to the pcap \p out (written under a temporary name, renamed at the
/// end) until a limit is reached, a stop is requested (SIGINT/SIGTERM once the app installed
/// roadslam/common/stop_signal.h's handlers, or requestStop()), or a recording source is exhausted;
/// what was recorded until then is a complete pcap.
/// Throws std::runtime_error naming \p out when it cannot be written, or when no packet at all
/// was recorded (the output is then not created).
RecordSummary recordToPcap(PacketSource& src, const std::string& out, const RecordLimits& limits);

}  // namespace roadslam::sources

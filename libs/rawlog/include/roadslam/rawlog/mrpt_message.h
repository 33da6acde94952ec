#pragma once
/// \file mrpt_message.h
/// MRPT's exception text on one line, and where a rawlog stopped being readable: what the rawlog
/// index and the rawlog replay report when MRPT cannot read a record.
#include <cstdint>
#include <string>

namespace roadslam::rawlog::detail {

/// MRPT nests exceptions ("==== MRPT exception ====\nMessage: ...\nOriginal exception: ..."); the
/// innermost "Message:" line names the cause on one line (else the text's first line).
inline std::string innermostMessage(const std::string& what) {
  const auto at = what.rfind("Message:");
  if (at == std::string::npos) return what.substr(0, what.find('\n'));
  std::string line = what.substr(at + 8, what.find('\n', at) - at - 8);
  line.erase(0, line.find_first_not_of(' '));
  return line;
}

/// Where reading a rawlog stopped before its end, in the words of every reader of rawlogs (the
/// replay, sources::RawlogPacketSource, and the index, RawlogIndex): "truncated record at
/// uncompressed byte N" when the data end inside a record (\p cause empty), else "unreadable record
/// at uncompressed byte N: CAUSE".
inline std::string stopPlace(uint64_t uncompressed_byte, const std::string& cause = "") {
  return (cause.empty() ? "truncated" : "unreadable") + std::string(" record at uncompressed byte ") +
         std::to_string(uncompressed_byte) + (cause.empty() ? "" : ": " + cause);
}

/// MRPT's way of saying a stream ended inside an object (it wraps its CExceptionEOF).
inline bool isCutShort(const std::string& what) {
  return what.find("Cannot read requested number of bytes") != std::string::npos;
}

}  // namespace roadslam::rawlog::detail

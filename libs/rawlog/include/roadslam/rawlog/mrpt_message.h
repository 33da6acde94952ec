#pragma once
/// \file mrpt_message.h
/// MRPT's exception text on one line: what the rawlog index and the rawlog replay report when MRPT
/// cannot read a record.
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

}  // namespace roadslam::rawlog::detail

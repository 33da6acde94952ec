// libFuzzer target: the candump parser must never crash; every accepted line must format back to
// a line that parses to the same frame.
#include <roadslam/can/candump.h>

#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  roadslam::can::CandumpReader reader(in, "fuzz");
  roadslam::can::CanFrame f, g;
  while (reader.next(f)) {
    const std::string line = roadslam::can::formatCandumpLine(f);
    const char* err = nullptr;
    if (line.empty() || !roadslam::can::parseCandumpLine(std::string_view(line).substr(0, line.size() - 1), g, &err)) {
      std::abort();
    }
    if (g != f) std::abort();
  }
  const auto& st = reader.stats();
  if (st.frames + st.bad + st.empty != st.lines) std::abort();  // every line accounted for
  return 0;
}

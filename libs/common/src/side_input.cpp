#include "roadslam/common/side_input.h"

#include <cstdio>

namespace roadslam {

std::string sideInputMismatch(const std::string& what, double first_s, double last_s, double recording_start_s,
                              double slack_s) {
  const bool before = recording_start_s < first_s - slack_s, after = recording_start_s > last_s + slack_s;
  if (!before && !after) return "";
  char buf[256];
  std::snprintf(buf, sizeof buf, " covers %.3f to %.3f s (%.1f s), but the recording starts at %.3f s, %.1f s %s it: "
                "another drive, or another clock", first_s, last_s, last_s - first_s, recording_start_s,
                before ? first_s - recording_start_s : recording_start_s - last_s, before ? "before" : "after");
  return what + buf;
}

}  // namespace roadslam

#include "roadslam/common/text_summary.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>

namespace roadslam {

std::string alignedLines(const SummaryLines& lines) {
  size_t width = 0;
  for (const auto& l : lines) width = std::max(width, l.first.size());
  std::string out;
  for (const auto& [label, value] : lines) {
    out += label;
    out.append(width - label.size() + 2, ' ');
    out += value;
    out += '\n';
  }
  return out;
}

std::string formatText(const char* fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  va_list ap2;
  va_copy(ap2, ap);
  const int n = std::vsnprintf(nullptr, 0, fmt, ap);
  va_end(ap);
  std::string s(n > 0 ? static_cast<size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(s.data(), s.size() + 1, fmt, ap2);
  va_end(ap2);
  return s;
}

std::string warningsValue(size_t count) {
  return count == 0 ? "none" : std::to_string(count) + " (on stderr and in summary.json)";
}

}  // namespace roadslam

#pragma once
/// \file text_summary.h
/// Summaries for a person: "label   value" lines with the values aligned in one column.

#include <string>
#include <utility>
#include <vector>

namespace roadslam {

using SummaryLines = std::vector<std::pair<std::string, std::string>>;

/// One line per entry, the values starting two spaces after the longest label; ends with '\n'.
std::string alignedLines(const SummaryLines& lines);

/// printf-style formatting into a std::string (for the values of alignedLines).
std::string formatText(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
/// The "warnings" line's value for \p count warnings: "none", or where the person finds them.
std::string warningsValue(size_t count);

}  // namespace roadslam

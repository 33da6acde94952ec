#pragma once
// Private helpers: read a text file line by line and parse a fixed count of numbers per line, so
// every format reports malformed input as "file:line: reason".

#include <functional>
#include <string>
#include <vector>

namespace roadslam::datasets::detail {

/// Calls \p on_line(numbers, line_no) for each non-empty, non-'#' line of \p path.
/// Throws naming the file when it cannot be opened.
void forEachNumberLine(const std::string& path,
                       const std::function<void(const std::vector<double>&, int)>& on_line);

/// Parses all whitespace-separated numbers of \p text; throws naming \p path:\p line_no on a
/// token that is not a number.
std::vector<double> parseNumbers(const std::string& text, const std::string& path, int line_no);

/// Throws "path:line: expected N numbers, got M" when \p v.size() != \p n.
void expectCount(const std::vector<double>& v, size_t n, const std::string& path, int line_no);

}  // namespace roadslam::datasets::detail

#include "roadslam/runfolder/csv.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdlib>
#include <stdexcept>

namespace roadslam::runfolder {

std::vector<std::string> splitCsvLine(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t i = 0; i <= line.size(); ++i) {
    if (i == line.size() || line[i] == ',') {
      out.push_back(line.substr(start, i - start));
      start = i + 1;
    }
  }
  if (!out.empty() && !out.back().empty() && out.back().back() == '\r') out.back().pop_back();
  return out;
}

std::string csvText(std::string s) {
  std::replace(s.begin(), s.end(), ',', ';');
  return s;
}

std::string format(const char* fmt, ...) {
  va_list ap, ap2;
  va_start(ap, fmt);
  va_copy(ap2, ap);
  const int n = std::vsnprintf(nullptr, 0, fmt, ap);
  va_end(ap);
  std::string out(static_cast<size_t>(std::max(n, 0)) + 1, '\0');
  std::vsnprintf(out.data(), out.size(), fmt, ap2);
  va_end(ap2);
  out.pop_back();
  return out;
}

CsvReader::CsvReader(const std::string& path, const std::vector<std::string>& needed) : path_(path), in_(path) {
  if (!in_) throw std::runtime_error(path + ": cannot be read");
  std::string header;
  if (!std::getline(in_, header)) throw std::runtime_error(path + ": empty, no header line");
  size_t c = 0;
  for (const auto& name : splitCsvLine(header)) col_[name] = c++;
  for (const auto& n : needed)
    if (!col_.count(n)) throw std::runtime_error(path + ": no column '" + n + "' in the header line");
}

bool CsvReader::next() {
  std::string line;
  while (std::getline(in_, line)) {
    ++line_;
    if (line.empty() || line == "\r") continue;
    row_ = splitCsvLine(line);
    return true;
  }
  return false;
}

size_t CsvReader::column(const std::string& name) const {
  const auto it = col_.find(name);
  if (it == col_.end()) throw std::runtime_error(path_ + ": no column '" + name + "' in the header line");
  return it->second;
}

const std::string& CsvReader::text(const std::string& name) const {
  static const std::string empty;
  const size_t c = column(name);
  return c < row_.size() ? row_[c] : empty;
}

double CsvReader::real(const std::string& name) const {
  const std::string& cell = text(name);
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  if (cell.empty() || *end != '\0')
    throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": column '" + name + "' is not a number: '" + cell + "'");
  return v;
}

double CsvReader::number(const std::string& name) const {
  const double v = real(name);
  if (!std::isfinite(v))
    throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": column '" + name + "' is not a number: '" + text(name) + "'");
  return v;
}

long CsvReader::integer(const std::string& name) const {
  const double v = number(name);
  if (v != std::floor(v) || std::abs(v) > 9e15)
    throw std::runtime_error(path_ + ":" + std::to_string(line_) + ": column '" + name + "' is not a whole number: '" +
                             text(name) + "'");
  return static_cast<long>(v);
}

}  // namespace roadslam::runfolder

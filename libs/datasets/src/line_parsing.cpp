#include "line_parsing.h"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace roadslam::datasets::detail {

std::vector<double> parseNumbers(const std::string& text, const std::string& path, int line_no) {
  std::vector<double> out;
  std::istringstream ss(text);
  std::string tok;
  while (ss >> tok) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end != '\0' || errno == ERANGE) {
      throw std::runtime_error(path + ":" + std::to_string(line_no) + ": '" + tok +
                               "' is not a number");
    }
    out.push_back(v);
  }
  return out;
}

void expectCount(const std::vector<double>& v, size_t n, const std::string& path, int line_no) {
  if (v.size() != n) {
    throw std::runtime_error(path + ":" + std::to_string(line_no) + ": expected " +
                             std::to_string(n) + " numbers, got " + std::to_string(v.size()));
  }
}

void forEachNumberLine(const std::string& path,
                       const std::function<void(const std::vector<double>&, int)>& on_line) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    on_line(parseNumbers(line, path, line_no), line_no);
  }
}

}  // namespace roadslam::datasets::detail

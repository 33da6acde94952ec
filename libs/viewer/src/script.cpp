#include <fstream>
#include <sstream>
#include <stdexcept>

#include "roadslam/viewer/replay.h"
#include "roadslam/viewer/window.h"

namespace roadslam::viewer {

std::vector<ScriptCommand> readScript(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot open script '" + path + "'");
  std::vector<ScriptCommand> out;
  std::string line;
  for (int n = 1; std::getline(f, line); ++n) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream ss(line);
    ScriptCommand c;
    c.line = n;
    ss >> c.verb;
    std::getline(ss >> std::ws, c.arg);
    const std::string where = path + ":" + std::to_string(n) + ": ";
    if (c.verb == "key") {
      if (!parseKey(c.arg)) throw std::runtime_error(where + "unknown key '" + c.arg + "'");
    } else if (c.verb == "wait" || c.verb == "select") {
      try {
        if (std::stod(c.arg) < 0) throw std::invalid_argument("negative");
      } catch (const std::exception&) {
        throw std::runtime_error(where + c.verb + " needs a number >= 0, not '" + c.arg + "'");
      }
    } else if (c.verb == "screenshot") {
      if (c.arg.empty()) throw std::runtime_error(where + "screenshot needs a PNG path");
    } else if (c.verb != "quit") {
      throw std::runtime_error(where + "unknown command '" + c.verb + "' (key, wait, select, screenshot, quit)");
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace roadslam::viewer

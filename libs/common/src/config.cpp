#include "roadslam/common/config.h"
#include "roadslam/common/checked_config.h"

#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace roadslam {
std::string configSource(const mrpt::config::CConfigFileBase& cfg) {
  if (auto f = dynamic_cast<const mrpt::config::CConfigFile*>(&cfg)) return f->getAssociatedFile() + ": ";
  if (auto f = dynamic_cast<const CheckedConfig*>(&cfg)) return f->path() + ": ";
  return "";
}

std::string keyLocation(const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key) {
  if (auto f = dynamic_cast<const CheckedConfig*>(&cfg); f && f->lineOf(section, key) > 0)
    return f->path() + ":" + std::to_string(f->lineOf(section, key)) + ": [" + section + "] " + key;
  return configSource(cfg) + "[" + section + "] " + key;
}

void requireValue(bool ok, const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
                  const std::string& what) {
  if (ok) return;
  const std::string v = cfg.read_string(section, key, "", false);
  throw std::runtime_error(keyLocation(cfg, section, key) + " = " + (v.empty() ? "(default)" : v) + ": " + what);
}

void requireValues(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   std::initializer_list<ValueCheck> checks) {
  for (const ValueCheck& c : checks) requireValue(c.ok, cfg, section, c.key, std::string("must be ") + c.bound);
}

namespace {
std::string raw(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                const std::string& key) {
  return cfg.read_string(section, key, "", false);
}
}  // namespace

std::unique_ptr<CheckedConfig> loadIniFile(const std::string& path) {
  return std::make_unique<CheckedConfig>(path);
}

double readDouble(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                  const std::string& key, double default_value) {
  const std::string s = raw(cfg, section, key);
  if (s.empty()) return default_value;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  if (end == s.c_str() || (end && *end != '\0') || errno == ERANGE) {
    throw std::runtime_error(keyLocation(cfg, section, key) + " = '" + s + "' is not a number");
  }
  return v;
}

int readInt(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
            const std::string& key, int default_value) {
  const std::string s = raw(cfg, section, key);
  if (s.empty()) return default_value;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  if (end == s.c_str() || (end && *end != '\0') || errno == ERANGE) {
    throw std::runtime_error(keyLocation(cfg, section, key) + " = '" + s + "' is not an integer");
  }
  return static_cast<int>(v);
}

bool readBool(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, bool default_value) {
  std::string s = raw(cfg, section, key);
  if (s.empty()) return default_value;
  std::transform(s.begin(), s.end(), s.begin(), ::tolower);
  if (s == "1" || s == "true" || s == "yes" || s == "on") return true;
  if (s == "0" || s == "false" || s == "no" || s == "off") return false;
  throw std::runtime_error(keyLocation(cfg, section, key) + " = '" + s + "' is not a boolean");
}

std::string readString(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                       const std::string& key, const std::string& default_value) {
  const std::string s = raw(cfg, section, key);
  return s.empty() ? default_value : s;
}

void rejectUnknownKeys(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                       const std::vector<std::string>& known) {
  const auto bad = unknownKeys(cfg, section, known);
  if (bad.empty()) return;
  std::string at;
  if (auto f = dynamic_cast<const CheckedConfig*>(&cfg)) at = f->path() + ":" + std::to_string(f->lineOf(section, bad.front())) + ": ";
  const std::string near = nearestName(bad.front(), known);
  throw std::runtime_error(at + "unknown key '" + bad.front() + "' in [" + section + "]" +
                           (near.empty() ? "" : " (nearest known: " + near + ")"));
}

std::vector<std::string> unknownKeys(const mrpt::config::CConfigFileBase& cfg,
                                     const std::string& section,
                                     const std::vector<std::string>& known) {
  std::vector<std::string> keys, out;
  cfg.getAllKeys(section, keys);
  for (const auto& k : keys) {
    if (std::find(known.begin(), known.end(), k) == known.end()) out.push_back(k);
  }
  return out;
}

}  // namespace roadslam

#pragma once
// Internal: a typo in an ini key must not go unseen (the default would silently apply).
#include <stdexcept>
#include <string>
#include <vector>

#include "roadslam/common/config.h"

namespace roadslam::mapping {

inline void rejectUnknownKeys(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                              const std::vector<std::string>& known) {
  const auto unknown = unknownKeys(cfg, section, known);
  if (!unknown.empty()) throw std::runtime_error("[" + section + "] unknown key '" + unknown.front() + "'");
}

}  // namespace roadslam::mapping

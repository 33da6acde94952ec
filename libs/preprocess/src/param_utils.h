#pragma once
// Private: ini reading with the thesis's short names accepted as aliases of the SI keys.

#include "roadslam/common/config.h"

#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>
#include <string>

namespace roadslam::preprocess::detail {

inline bool hasKey(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   const std::string& key) {
  return !cfg.read_string(section, key, "", false).empty();
}

/// Value of \p key, or of \p alias (same unit) when only the alias is set; both set is an error.
inline double readDoubleAlias(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                              const std::string& key, const std::string& alias, double def) {
  const bool k = hasKey(cfg, section, key), a = hasKey(cfg, section, alias);
  if (k && a) {
    throw std::runtime_error("[" + section + "] sets both '" + key + "' and its alias '" + alias + "'");
  }
  return readDouble(cfg, section, a ? alias : key, def);
}

inline int readIntAlias(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                        const std::string& key, const std::string& alias, int def) {
  const bool k = hasKey(cfg, section, key), a = hasKey(cfg, section, alias);
  if (k && a) {
    throw std::runtime_error("[" + section + "] sets both '" + key + "' and its alias '" + alias + "'");
  }
  return readInt(cfg, section, a ? alias : key, def);
}

/// Throws naming section/key when \p ok is false.
inline void require(bool ok, const std::string& section, const std::string& key,
                    const std::string& what) {
  if (!ok) throw std::runtime_error("[" + section + "] " + key + ": " + what);
}

}  // namespace roadslam::preprocess::detail

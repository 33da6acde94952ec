#pragma once
/// \file config.h
/// Ini helpers on top of MRPT's config classes: every component's Params loads from and saves to a
/// section with these, so a missing file or a malformed value is reported with the file and key.

#include <mrpt/config/CConfigFileBase.h>

#include "roadslam/common/checked_config.h"

#include <memory>
#include <initializer_list>
#include <string>

namespace roadslam {

/// Opens an ini file; throws std::runtime_error naming the file when it is missing or unreadable.
/// It records the keys read, so a job can report the ones no component knows (checked_config.h).
std::unique_ptr<CheckedConfig> loadIniFile(const std::string& path);

/// "file: " when \p cfg was read from a file (CConfigFile or CheckedConfig), else "": the start of an
/// error message about one of its keys.
std::string configSource(const mrpt::config::CConfigFileBase& cfg);

/// "FILE:LINE: [section] key" (the key's line when \p cfg is a CheckedConfig that has it), else
/// "file: [section] key" or "[section] key": the start of an error message about one value.
std::string keyLocation(const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key);

/// Throws std::runtime_error "FILE:LINE: [section] key = value: \p what" unless \p ok: the range check
/// of one loaded value, naming the key as the ini wrote it.
void requireValue(bool ok, const mrpt::config::CConfigFileBase& cfg, const std::string& section, const std::string& key,
                  const std::string& what);
/// One key's range check: the key, whether its value is in range, the bound ("> 0", "in (0, 1)").
struct ValueCheck {
  const char* key;
  bool ok;
  const char* bound;
};
/// requireValue(ok, cfg, section, key, "must be " + bound) for each check, in order.
void requireValues(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   std::initializer_list<ValueCheck> checks);

/// Reads a double; throws naming section/key (and the source) when the value is not a number.
double readDouble(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                  const std::string& key, double default_value);
int readInt(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
            const std::string& key, int default_value);
bool readBool(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, bool default_value);
std::string readString(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                       const std::string& key, const std::string& default_value);

/// Throws std::runtime_error for the first key of \p section that is not in \p known, naming the
/// file and line (when \p cfg is a CheckedConfig) and the nearest known key: for components that
/// know their keys up front and check them themselves.
void rejectUnknownKeys(const mrpt::config::CConfigFileBase& cfg, const std::string& section,
                       const std::vector<std::string>& known);

/// Keys present in \p section that are not in \p known: reported so a typo in an ini never goes unseen.
std::vector<std::string> unknownKeys(const mrpt::config::CConfigFileBase& cfg,
                                     const std::string& section,
                                     const std::vector<std::string>& known);

}  // namespace roadslam

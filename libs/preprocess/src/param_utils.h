#pragma once
// Private: the range check of the preprocess Params (the thesis aliases are ParamTable::numOrAlias).

#include "roadslam/common/config.h"

#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>
#include <string>

namespace roadslam::preprocess::detail {

/// Throws naming section/key when \p ok is false.
inline void require(bool ok, const std::string& section, const std::string& key,
                    const std::string& what) {
  if (!ok) throw std::runtime_error("[" + section + "] " + key + ": " + what);
}

}  // namespace roadslam::preprocess::detail

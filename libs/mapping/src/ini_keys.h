#pragma once
// Internal: a typo in an ini key must not go unseen (the default would silently apply).
#include <stdexcept>
#include <string>
#include <vector>

#include "roadslam/common/config.h"

namespace roadslam::mapping {

using roadslam::rejectUnknownKeys;

}  // namespace roadslam::mapping

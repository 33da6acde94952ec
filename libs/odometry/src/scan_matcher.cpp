#include "roadslam/odometry/scan_matcher.h"

#include "registration_matcher.h"
#include "voxel_map_matcher.h"

namespace roadslam::odometry {

std::unique_ptr<ScanMatcher> makeScanMatcher(const Params& p) {
  switch (p.matcher) {
    case Matcher::VoxelMap: return std::make_unique<VoxelMapMatcher>(p);
    case Matcher::Registration: return std::make_unique<RegistrationMatcher>(p);
  }
  return std::make_unique<VoxelMapMatcher>(p);
}

}  // namespace roadslam::odometry

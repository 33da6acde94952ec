#pragma once
// The shared KITTI recordings the datasets tests read (../shared/data/kitti, README there).
#include <string>

namespace roadslam::datasets::test {

inline const std::string kOdo = std::string(ROADSLAM_SHARED_DATA) + "/kitti/odometry-00-first16/";
inline const std::string kRaw = std::string(ROADSLAM_SHARED_DATA) + "/kitti/raw-2011_09_26-0001/";

}  // namespace roadslam::datasets::test

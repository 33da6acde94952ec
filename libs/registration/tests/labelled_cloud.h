#pragma once
// A test scene's points with their road labels, as the voxel map takes them.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace roadslam::registration::test {

struct Cloud {
  std::vector<Eigen::Vector3d> points;
  std::vector<uint8_t> ground;
  void add(const Eigen::Vector3d& p, bool is_ground) {
    points.push_back(p);
    ground.push_back(is_ground ? 1 : 0);
  }
};

}  // namespace roadslam::registration::test

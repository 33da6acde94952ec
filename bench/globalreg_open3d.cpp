// Open3D 0.16 (Debian libopen3d-dev) FPFH + Fast Global Registration (Zhou et al. 2016) + point-to-plane
// ICP, with the same voxels, radii and reach as ours (GlobalParams defaults).
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/FastGlobalRegistration.h>
#include <open3d/pipelines/registration/Feature.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include "globalreg_peers.h"

namespace roadslam::bench {
namespace o3g = open3d::geometry;
namespace o3r = open3d::pipelines::registration;

bool open3dAvailable() { return true; }
std::string open3dSettings() {
  return "open3d: VoxelDownSample 1.0 m, normals hybrid(2.0 m, 30) towards the sensor, FPFH hybrid(5.0 m, 100), "
         "FastGlobalRegistrationBasedOnFeatureMatching (max corr. 1.5 m, defaults otherwise), then RegistrationICP "
         "point-to-plane at 0.5 m voxels, 1.0 m reach";
}

GlobalPeerResult open3dFpfhFgr(const registration::PointCloud& target, const registration::PointCloud& source) {
  auto prep = [](const registration::PointCloud& pts, double voxel) {
    auto pc = o3g::PointCloud(pts).VoxelDownSample(voxel);
    pc->EstimateNormals(o3g::KDTreeSearchParamHybrid(2.0, 30));
    pc->OrientNormalsTowardsCameraLocation(Eigen::Vector3d::Zero());
    return pc;
  };
  const auto t1 = prep(target, 1.0), s1 = prep(source, 1.0);
  const auto ft = o3r::ComputeFPFHFeature(*t1, o3g::KDTreeSearchParamHybrid(5.0, 100));
  const auto fs = o3r::ComputeFPFHFeature(*s1, o3g::KDTreeSearchParamHybrid(5.0, 100));
  o3r::FastGlobalRegistrationOption opt;
  opt.maximum_correspondence_distance_ = 1.5;
  const o3r::RegistrationResult g = o3r::FastGlobalRegistrationBasedOnFeatureMatching(*s1, *t1, *fs, *ft, opt);
  const auto t05 = prep(target, 0.5), s05 = prep(source, 0.5);
  const o3r::RegistrationResult r = o3r::RegistrationICP(*s05, *t05, 1.0, g.transformation_,
                                                          o3r::TransformationEstimationPointToPlane(), o3r::ICPConvergenceCriteria());
  GlobalPeerResult out;
  out.T_fgr.matrix() = g.transformation_;
  out.T_target_source.matrix() = r.transformation_;
  return out;
}

}  // namespace roadslam::bench

// Open3D 0.16 (Debian libopen3d-dev) point-to-plane ICP behind PeerMethod; built only with
// -DROADSLAM_BENCH_PEERS=ON.
#include <open3d/geometry/KDTreeSearchParam.h>
#include <open3d/geometry/PointCloud.h>
#include <open3d/pipelines/registration/Registration.h>
#include <open3d/pipelines/registration/TransformationEstimation.h>

#include "peers.h"

namespace roadslam::bench {
namespace {
namespace o3r = open3d::pipelines::registration;

// Target normals from 30 neighbours within 1 m (two 0.5 m voxels); the same 2 m reach as ours;
// Open3D's default convergence criteria (relative fitness and RMSE 1e-6, 30 iterations).
class Open3dPointToPlane : public PeerMethod {
 public:
  std::string name() const override { return "open3d_icp_point_to_plane"; }
  std::string settings() const override {
    return "open3d RegistrationICP point-to-plane, max correspondence 2.0 m, target normals hybrid(1.0 m, 30), "
           "ICPConvergenceCriteria defaults";
  }
  void prepare(const registration::PointCloud& target, const registration::PointCloud& source) override {
    target_ = open3d::geometry::PointCloud(target);
    source_ = open3d::geometry::PointCloud(source);
  }
  PeerResult run() override {
    target_.EstimateNormals(open3d::geometry::KDTreeSearchParamHybrid(1.0, 30));
    const o3r::RegistrationResult r =
        o3r::RegistrationICP(source_, target_, 2.0, Eigen::Matrix4d::Identity(), o3r::TransformationEstimationPointToPlane(),
                             o3r::ICPConvergenceCriteria());
    PeerResult out;
    out.T_target_source.matrix() = r.transformation_;
    out.converged = true;  // Open3D reports no convergence flag
    return out;
  }

 private:
  open3d::geometry::PointCloud target_, source_;
};

}  // namespace

void addOpen3d(PeerList& out) { out.push_back(std::make_unique<Open3dPointToPlane>()); }

}  // namespace roadslam::bench

// PCL 1.13 (Debian libpcl-dev) NDT and GICP behind PeerMethod; built only with -DROADSLAM_BENCH_PEERS=ON.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/gicp.h>
#include <pcl/registration/ndt.h>

#include "peers.h"

namespace roadslam::bench {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

Cloud::Ptr toPcl(const registration::PointCloud& pts) {
  Cloud::Ptr c(new Cloud);
  c->reserve(pts.size());
  for (const auto& p : pts) c->push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  return c;
}

PeerResult finish(const Eigen::Matrix4f& T, bool converged, int iterations) {
  PeerResult r;
  r.T_target_source.matrix() = T.cast<double>();
  r.converged = converged;
  r.iterations = iterations;
  return r;
}

class PclPeer : public PeerMethod {
 public:
  void prepare(const registration::PointCloud& target, const registration::PointCloud& source) override {
    target_ = toPcl(target);
    source_ = toPcl(source);
  }

 protected:
  Cloud::Ptr target_, source_;
  Cloud aligned_;
};

// Settings of the PCL NDT tutorial except epsilon: with 0.01 it stops after one iteration here.
class PclNdt : public PclPeer {
 public:
  std::string name() const override { return "pcl_ndt"; }
  std::string settings() const override {
    return "pcl::NormalDistributionsTransform resolution 1.0 m, step 0.1 m, epsilon 1e-4, max 100 iterations";
  }
  PeerResult run() override {
    pcl::NormalDistributionsTransform<pcl::PointXYZ, pcl::PointXYZ> ndt;
    ndt.setResolution(1.0f);
    ndt.setStepSize(0.1);
    ndt.setTransformationEpsilon(1e-4);
    ndt.setMaximumIterations(100);
    ndt.setInputTarget(target_);
    ndt.setInputSource(source_);
    ndt.align(aligned_, Eigen::Matrix4f::Identity());
    return finish(ndt.getFinalTransformation(), ndt.hasConverged(), ndt.getFinalNumIteration());
  }
};

// PCL defaults (20 neighbours per covariance, its epsilons) with the same 2 m reach as ours: the
// default reach (unbounded) pairs every point.
class PclGicp : public PclPeer {
 public:
  std::string name() const override { return "pcl_gicp"; }
  std::string settings() const override {
    return "pcl::GeneralizedIterativeClosestPoint max correspondence 2.0 m, other settings PCL defaults";
  }
  PeerResult run() override {
    pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
    gicp.setMaxCorrespondenceDistance(2.0);
    gicp.setInputTarget(target_);
    gicp.setInputSource(source_);
    gicp.align(aligned_, Eigen::Matrix4f::Identity());
    return finish(gicp.getFinalTransformation(), gicp.hasConverged(), 0);
  }
};

}  // namespace

void addPcl(PeerList& out) {
  out.push_back(std::make_unique<PclNdt>());
  out.push_back(std::make_unique<PclGicp>());
}

}  // namespace roadslam::bench

// Ours (the registration library with its default Params) and MRPT CICP::Align3D behind PeerMethod.
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/slam/CICP.h>
#include <roadslam/registration/registration.h>

#include <cstdio>

#include "peers.h"

namespace roadslam::bench {
namespace {
namespace reg = registration;

class Ours : public PeerMethod {
 public:
  Ours(std::string name, reg::Method m) : name_(std::move(name)) { prm_.method = m; }
  std::string name() const override { return name_; }
  std::string settings() const override {
    char buf[160];
    std::snprintf(buf, sizeof buf, "roadslam %s, default Params (NDT %.2g m, %d levels; ICP reach %.2g m, %d iterations)",
                  reg::toString(prm_.method).c_str(), prm_.ndt_resolution_m, prm_.ndt_levels,
                  prm_.max_correspondence_distance_m, prm_.max_iterations);
    return buf;
  }
  void prepare(const reg::PointCloud& target, const reg::PointCloud& source) override {
    target_ = &target;
    source_ = &source;
  }
  PeerResult run() override {
    const reg::Target t(*target_, prm_);
    const reg::RegistrationResult r = reg::align(t, *source_, Eigen::Isometry3d::Identity(), prm_);
    return {r.T_target_source, r.converged, r.iterations};
  }

 private:
  std::string name_;
  reg::Params prm_;
  const reg::PointCloud* target_ = nullptr;
  const reg::PointCloud* source_ = nullptr;
};

mrpt::maps::CSimplePointsMap toMrpt(const reg::PointCloud& pts) {
  mrpt::maps::CSimplePointsMap m;
  m.reserve(pts.size());
  for (const auto& p : pts) {
    m.insertPointFast(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  }
  m.mark_as_modified();
  return m;
}

class MrptCicp : public PeerMethod {
 public:
  std::string name() const override { return "mrpt_cicp_align3d"; }
  std::string settings() const override { return "mrpt::slam::CICP::Align3D, MRPT defaults (icpClassic, point-to-point)"; }
  void prepare(const reg::PointCloud& target, const reg::PointCloud& source) override {
    target_ = toMrpt(target);
    source_ = toMrpt(source);
  }
  PeerResult run() override {
    mrpt::slam::CICP icp;
    mrpt::slam::CICP::TReturnInfo info;
    const auto pdf = icp.Align3D(&target_, &source_, mrpt::poses::CPose3D(), info);
    PeerResult r;
    r.T_target_source.matrix() = pdf->getMeanVal().getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
    r.converged = info.nIterations < icp.options.maxIterations;
    r.iterations = static_cast<int>(info.nIterations);
    return r;
  }

 private:
  mrpt::maps::CSimplePointsMap target_, source_;
};

}  // namespace

void addOurs(PeerList& out) {
  out.push_back(std::make_unique<Ours>("ours_icp_point_to_plane", reg::Method::IcpPointToPlane));
  out.push_back(std::make_unique<Ours>("ours_ndt", reg::Method::Ndt));
}
void addMrpt(PeerList& out) { out.push_back(std::make_unique<MrptCicp>()); }

}  // namespace roadslam::bench

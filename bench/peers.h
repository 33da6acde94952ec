#pragma once
// Registration methods compared by bench_peers behind one interface: ours, MRPT, and (with
// -DROADSLAM_BENCH_PEERS=ON) PCL and Open3D. Peer headers stay in their own .cpp files.

#include <roadslam/registration/point_cloud.h>

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

namespace roadslam::bench {

struct PeerResult {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();  ///< source -> target [m]
  bool converged = false;
  int iterations = 0;  ///< as the method reports it, 0 when it does not [-]
};

class PeerMethod {
 public:
  virtual ~PeerMethod() = default;
  virtual std::string name() const = 0;
  /// One line of the settings used (printed with the table).
  virtual std::string settings() const = 0;
  /// Converts the clouds (lidar frames [m]) to the method's types: not timed.
  virtual void prepare(const registration::PointCloud& target, const registration::PointCloud& source) = 0;
  /// Everything from the converted clouds to the pose (search structures, normals, covariances
  /// included), identity initial guess: timed.
  virtual PeerResult run() = 0;
};

using PeerList = std::vector<std::unique_ptr<PeerMethod>>;
void addOurs(PeerList& out);  ///< roadslam ICP point-to-plane and NDT, default Params
void addMrpt(PeerList& out);  ///< mrpt::slam::CICP::Align3D, MRPT defaults
void addPcl(PeerList& out);     ///< PCL NDT and GICP (no-op without ROADSLAM_BENCH_PEERS)
void addOpen3d(PeerList& out);  ///< Open3D point-to-plane ICP (no-op without ROADSLAM_BENCH_PEERS)

}  // namespace roadslam::bench

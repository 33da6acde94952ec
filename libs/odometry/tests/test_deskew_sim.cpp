// Deskewing against the simulator's exact motion: each decoded point, mapped by the true lidar
// pose at its own firing time, is where the world surface is (the simulator's frame test); the
// deskewed sweep mapped by the single true pose at the sweep stamp must land there too.
#include <gtest/gtest.h>

#include <cmath>

#include "roadslam/odometry/deskew.h"
#include "roadslam/sim/simulator.h"
#include "roadslam/sim/eigen.h"
#include "roadslam/sim/sweep_sink.h"

using namespace roadslam;

namespace {

using sim::toEigen;

}  // namespace

TEST(DeskewSim, TrueMotionDeskewPutsPointsOnTheWorld) {
  auto p = sim::ScenarioParams::fromFile(std::string(ROADSLAM_SOURCE_DIR) + "/ini/sim/highway.ini");
  p.trajectory.start_standing_s = 0;
  p.duration_s = 8.0;
  p.lidar.range_noise_m = 0;
  p.lidar.jitter_deg = 0;
  sim::Simulator s(p);
  std::vector<Scan> sweeps;
  sim::SweepSink sink([&](Scan&& sc) { sweeps.push_back(std::move(sc)); });
  s.run(sink);
  ASSERT_GT(sweeps.size(), 70u);
  double err_deskew = 0, err_raw = 0;
  size_t n = 0;
  for (size_t k = sweeps.size() - 10; k + 1 < sweeps.size(); ++k) {
    const Scan& sc = sweeps[k];
    const double t0 = sc.stamp_s - static_cast<double>(p.start_epoch_s);
    const Eigen::Isometry3d T0 = toEigen(s.lidar().lidarPose(t0));
    const Eigen::Isometry3d T1 = toEigen(s.lidar().lidarPose(t0 + 0.1));
    const auto des = odometry::deskew(sc, T0.inverse() * T1, 0.1);
    for (size_t i = 0; i < sc.points.size(); i += 7) {
      const auto& q = sc.points[i];
      const Eigen::Vector3d truth = toEigen(s.lidar().lidarPose(t0 + q.t)) * Eigen::Vector3d(q.x, q.y, q.z);
      err_deskew += (T0 * des[i] - truth).norm();
      err_raw += (T0 * Eigen::Vector3d(q.x, q.y, q.z) - truth).norm();
      ++n;
    }
  }
  err_deskew /= n;
  err_raw /= n;
  std::cout << "mean point error: deskewed " << err_deskew << " m, raw " << err_raw << " m\n";
  EXPECT_LT(err_deskew, 0.01);
  EXPECT_GT(err_raw, 20 * err_deskew);
}

#include <cerrno>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/mapping/maps.h"

namespace roadslam::mapping {

void writeSimpleMap(const std::string& path, const std::vector<Keyframe>& kfs, const PoseVector& T_map_kf,
                    double sigma_t_m, double sigma_r_rad) {
  mrpt::maps::CSimpleMap sm;
  for (size_t k = 0; k < kfs.size() && k < T_map_kf.size(); ++k) {
    auto pc = mrpt::maps::CSimplePointsMap::Create();
    pc->reserve(kfs[k].points_lidar.size());
    for (const auto& q : kfs[k].points_lidar) pc->insertPointFast(q.x(), q.y(), q.z());
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    obs->pointcloud = pc;
    obs->sensorLabel = "lidar";
    obs->timestamp = mrpt::Clock::fromDouble(kfs[k].stamp_s);
    auto sf = mrpt::obs::CSensoryFrame::Create();
    sf->insert(obs);
    mrpt::math::CMatrixDouble44 M;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) M(r, c) = T_map_kf[k].matrix()(r, c);
    mrpt::math::CMatrixDouble66 cov;
    cov.setZero();
    for (int i = 0; i < 3; ++i) cov(i, i) = sigma_t_m * sigma_t_m;
    for (int i = 3; i < 6; ++i) cov(i, i) = sigma_r_rad * sigma_r_rad;
    auto pdf = mrpt::poses::CPose3DPDFGaussian::Create(mrpt::poses::CPose3D::FromHomogeneousMatrix(M), cov);
    sm.insert(pdf, sf);
  }
  TempFile tmp(path);
  errno = 0;
  if (!sm.saveToFile(tmp.path())) throw std::runtime_error(tmp.failure("simplemap"));
  tmp.commit();
}

}  // namespace roadslam::mapping

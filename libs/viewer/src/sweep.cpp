#include "roadslam/viewer/sweep.h"

#include <mrpt/core/Clock.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <bitset>
#include <cstdio>
#include <sstream>

#include "roadslam/rawlog/mrpt_stamp.h"
#include "roadslam/velodyne/decoder.h"
#include "roadslam/velodyne/model_choice.h"

namespace roadslam::viewer {

namespace {
Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.matrix() = p.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
  return T;
}

/// The model of a recorded sweep (model_choice.h over its own packets, about 75 of a VLP-16 turn);
/// where their layout is inconclusive, the laser count of the calibration the recorder stored
/// (roadslam-rawlog convert and roadslam-grab store the model they decoded) over the product byte.
struct ObservationModel {
  velodyne::Model model = velodyne::Model::Unknown;
  std::string source, warning;
};
ObservationModel observationModel(const mrpt::obs::CObservationVelodyneScan& v) {
  velodyne::LayoutDetector layout;
  for (const auto& raw : v.scan_packets) layout.add(reinterpret_cast<const uint8_t*>(&raw), velodyne::kDataPacketSize);
  const velodyne::ModelChoice c = velodyne::chooseModel(velodyne::Model::Unknown, layout.verdict(),
                                                        "roadslam-rawlog convert --model");
  const auto lasers = v.calibration.laser_corrections.size();
  const auto stored = lasers == 16 ? velodyne::Model::VLP16 : lasers == 32 ? velodyne::Model::HDL32 : velodyne::Model::Unknown;
  if (c.layout.model == velodyne::Model::Unknown && stored != velodyne::Model::Unknown)
    return {stored, "rawlog calibration", ""};
  return {c.model, velodyne::toString(c.source), c.warning};
}

std::optional<SweepPoints> velodyneSweep(const mrpt::obs::CObservationVelodyneScan& v) {
  SweepPoints s;
  s.stamp_s = rawlog::stampSeconds(v.timestamp);
  s.T_base_lidar = toIsometry(v.sensorPose);
  s.packets = v.scan_packets.size();
  const ObservationModel om = observationModel(v);
  s.model = velodyne::displayName(om.model);
  s.model_source = om.source;
  s.model_warning = om.warning;
  velodyne::DecoderParams dp;
  dp.model = om.model;
  const velodyne::Decoder decoder(dp);
  s.points.reserve(v.scan_packets.size() * 384);
  std::vector<ScanPoint> pkt;
  double t_first = 0;
  bool first = true;
  std::bitset<64> rings;
  for (const auto& raw : v.scan_packets) {
    pkt.clear();
    const auto* b = reinterpret_cast<const uint8_t*>(&raw);
    velodyne::PacketInfo info;
    if (decoder.decode(b, velodyne::kDataPacketSize, pkt, &info) != velodyne::DecodeStatus::Ok) continue;
    double t_pkt = info.timestamp_us * 1e-6;
    if (first) t_first = t_pkt, first = false;
    if (t_pkt < t_first - 1800) t_pkt += 3600;  // the sensor's counter wraps at the hour
    if (info.mode == velodyne::ReturnMode::Dual) s.returns = 2;
    for (auto& p : pkt) {
      p.t = float(p.t + (t_pkt - t_first));
      rings.set(std::min<uint16_t>(p.ring, 63));
      s.points.push_back(p);
    }
  }
  for (const auto& p : s.points) s.span_s = std::max(s.span_s, double(p.t));
  s.has_rings = s.has_times = s.has_intensity = true;
  s.rings = int(rings.count());
  return s;
}

std::optional<SweepPoints> cloudSweep(const mrpt::obs::CObservationPointCloud& c) {
  if (!c.pointcloud) return std::nullopt;
  SweepPoints s;
  s.stamp_s = rawlog::stampSeconds(c.timestamp);
  s.T_base_lidar = toIsometry(c.sensorPose);
  s.model = "point cloud";
  const auto& xs = c.pointcloud->getPointsBufferRef_x();
  const auto& ys = c.pointcloud->getPointsBufferRef_y();
  const auto& zs = c.pointcloud->getPointsBufferRef_z();
  const auto* xyzi = dynamic_cast<const mrpt::maps::CPointsMapXYZI*>(c.pointcloud.get());
  s.has_intensity = xyzi != nullptr;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    ScanPoint p;
    p.x = xs[i], p.y = ys[i], p.z = zs[i];
    if (xyzi) p.intensity = xyzi->getPointIntensity(i);
    s.points.push_back(p);
  }
  return s;
}
}  // namespace

std::optional<SweepPoints> sweepOf(const mrpt::obs::CObservation& obs) {
  if (const auto* v = dynamic_cast<const mrpt::obs::CObservationVelodyneScan*>(&obs)) return velodyneSweep(*v);
  if (const auto* c = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&obs)) return cloudSweep(*c);
  return std::nullopt;
}

std::string describe(const mrpt::obs::CObservation& obs, const SweepPoints* s) {
  if (!s) {
    std::ostringstream os;
    obs.getDescriptionAsText(os);
    return os.str();
  }
  const Eigen::Vector3d t = s->T_base_lidar.translation();
  const Eigen::Vector3d ypr = s->T_base_lidar.rotation().eulerAngles(2, 1, 0) * 180.0 / M_PI;
  std::string cls = obs.GetRuntimeClass()->className;
  cls = cls.substr(cls.rfind(':') == std::string::npos ? 0 : cls.rfind(':') + 1);
  const std::string model = s->model + (s->model_source.empty() ? "" : " (by " + s->model_source + ")");
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "class       %s\nlabel       %s\ntime        %.6f s\nmodel       %s\npackets     %zu\n"
                "points      %zu\nrings       %d\nreturns     %d\ntime span   %.1f ms\n"
                "sensor pose x %.2f y %.2f z %.2f m, yaw %.1f pitch %.1f roll %.1f deg\n",
                cls.c_str(), obs.sensorLabel.c_str(), s->stamp_s, model.c_str(),
                s->packets, s->points.size(), s->rings, s->returns, s->span_s * 1e3, t.x(), t.y(), t.z(),
                ypr.x(), ypr.y(), ypr.z());
  return buf;
}

}  // namespace roadslam::viewer

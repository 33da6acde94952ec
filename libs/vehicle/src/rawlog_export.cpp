#include <roadslam/can/candump.h>
#include <roadslam/common/atomic_file.h>
#include <roadslam/common/config.h>
#include <roadslam/common/param_table.h>
#include <roadslam/vehicle/rawlog_export.h>

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/datetime.h>

#include <cmath>
#include <stdexcept>

namespace roadslam::vehicle {

void RawlogExportParams::fields(ParamTable& t) {
  t.text("odometry_label", odometry_label);
  t.text("imu_label", imu_label);
  t.text("gps_label", gps_label);
  t.flag("write_sidecar", write_sidecar);
}

void RawlogExportParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
}

void RawlogExportParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

std::string sidecarPath(const std::string& rawlog_path) {
  const std::string ext = ".rawlog";
  if (rawlog_path.size() > ext.size() && rawlog_path.compare(rawlog_path.size() - ext.size(), ext.size(), ext) == 0) {
    return rawlog_path.substr(0, rawlog_path.size() - ext.size()) + ".candump.log";
  }
  return rawlog_path + ".candump.log";
}

namespace {
mrpt::Clock::time_point stamp(double t_s) { return mrpt::Clock::fromDouble(t_s); }

void writeImu(mrpt::serialization::CArchive& ar, const VehicleState& s, UpdateMask mask, const std::string& label) {
  mrpt::obs::CObservationIMU imu;
  imu.sensorLabel = label;
  imu.timestamp = stamp(s.t_s);
  if (mask & bit(Quantity::kYawRate)) imu.set(mrpt::obs::IMU_WZ, s.value(Quantity::kYawRate));
  if (mask & bit(Quantity::kAccelX)) imu.set(mrpt::obs::IMU_X_ACC, s.value(Quantity::kAccelX));
  if (mask & bit(Quantity::kAccelY)) imu.set(mrpt::obs::IMU_Y_ACC, s.value(Quantity::kAccelY));
  ar << imu;
}

}  // namespace

std::shared_ptr<mrpt::obs::CObservationGPS> gpsObservation(const VehicleState& s, const std::string& label) {
  auto gps = std::make_shared<mrpt::obs::CObservationGPS>();
  gps->sensorLabel = label;
  gps->timestamp = stamp(s.t_s);
  gps->originalReceivedTimestamp = gps->timestamp;
  mrpt::obs::gnss::Message_NMEA_GGA gga;
  gga.fields.latitude_degrees = s.value(Quantity::kLatitude);
  gga.fields.longitude_degrees = s.value(Quantity::kLongitude);
  if (s.has(Quantity::kGnssHeight)) {
    gga.fields.altitude_meters = s.value(Quantity::kGnssHeight);
    gga.fields.orthometric_altitude = gga.fields.altitude_meters;
  }
  gga.fields.fix_quality = 1;
  const double tod = std::fmod(s.t_s, 86400.0);
  gga.fields.UTCTime.hour = static_cast<uint8_t>(tod / 3600);
  gga.fields.UTCTime.minute = static_cast<uint8_t>(std::fmod(tod, 3600) / 60);
  gga.fields.UTCTime.sec = std::fmod(tod, 60.0);
  gps->setMsg(gga);
  return gps;
}

RawlogExportStats exportRawlog(const std::vector<can::CanFrame>& frames, VehicleDecoder& decoder,
                               const DeadReckoningParams& dr_params, const RawlogExportParams& params,
                               const std::string& rawlog_path) {
  RawlogExportStats st;
  const std::string tmp = tempPathFor(rawlog_path);
  {
    mrpt::io::CFileGZOutputStream out;
    if (!out.open(tmp)) throw std::runtime_error("cannot write rawlog '" + tmp + "'");
    auto ar = mrpt::serialization::archiveFrom(out);
    DeadReckoning dr(dr_params, decoder.params());
    VehicleState s;
    constexpr UpdateMask kImuMask = bit(Quantity::kYawRate) | bit(Quantity::kAccelX) | bit(Quantity::kAccelY);
    for (const can::CanFrame& f : frames) {
      const UpdateMask mask = decoder.process(f, s);
      if (!mask) continue;
      if (dr.update(s, mask)) {
        mrpt::obs::CObservationOdometry odo;
        odo.sensorLabel = params.odometry_label;
        odo.timestamp = stamp(s.t_s);
        const Pose2D& p = dr.pose();
        odo.odometry = mrpt::poses::CPose2D(p.x_m, p.y_m, p.yaw_rad);
        odo.hasVelocities = true;
        odo.velocityLocal = mrpt::math::TTwist2D(p.v_mps, 0.0, p.w_radps);
        ar << odo;
        ++st.odometry;
      }
      if (mask & kImuMask) {
        writeImu(ar, s, mask, params.imu_label);
        ++st.imu;
      }
      if (gpsUpdated(s, mask)) {
        ar << *gpsObservation(s, params.gps_label);
        ++st.gps;
      }
    }
    out.close();
  }
  commitTempFile(tmp, rawlog_path);
  if (params.write_sidecar) {
    st.sidecar_path = sidecarPath(rawlog_path);
    can::writeCandumpFile(st.sidecar_path, frames);
    st.sidecar_frames = frames.size();
  }
  return st;
}

}  // namespace roadslam::vehicle

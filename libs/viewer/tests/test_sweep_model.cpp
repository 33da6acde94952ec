// The model a recorded sweep is decoded as (sweep.h): its own packets' layout over a product byte that
// disagrees, else the calibration stored with it; packets made by the encoder, whose layout is known.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "roadslam/velodyne/encoder.h"
#include "roadslam/viewer/sweep.h"

using namespace roadslam;
using mrpt::obs::CObservationVelodyneScan;

namespace {

/// \p n packets of a VLP-16 turning at 10 Hz in a 5 m cylinder, product byte \p product.
CObservationVelodyneScan vlp16Sweep(int n, velodyne::Model product) {
  CObservationVelodyneScan v;
  v.scan_packets.resize(std::size_t(n));
  for (int k = 0; k < n; ++k) {
    std::array<velodyne::FiringSequence, velodyne::kVlp16SequencesPerPacket> seq{};
    const double t_pkt = k * velodyne::kVlp16SequencesPerPacket * velodyne::kVlp16SequencePeriod_s;
    for (int q = 0; q < velodyne::kVlp16SequencesPerPacket; ++q) {
      seq[q].azimuth_deg = std::fmod(3600.0 * (t_pkt + q * velodyne::kVlp16SequencePeriod_s), 360.0);
      for (auto& r : seq[q].strongest) r = {5.0f, 40};
    }
    const auto bytes = velodyne::encodeVlp16Packet(seq, 1000000u + uint32_t(std::lround(t_pkt * 1e6)),
                                                   velodyne::ReturnMode::Strongest, product);
    std::memcpy(&v.scan_packets[std::size_t(k)], bytes.data(), bytes.size());
  }
  return v;
}

}  // namespace

TEST(SweepModel, LayoutOverAByteThatDisagrees) {
  const auto s = viewer::sweepOf(vlp16Sweep(40, velodyne::Model::HDL32));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->model, "VLP-16");
  EXPECT_EQ(s->model_source, "packet layout");
  EXPECT_NE(s->model_warning.find("but product byte 0x21 says HDL-32E; decoding as VLP-16"), std::string::npos)
      << s->model_warning;
  // The VLP-16's elevations (+-15 deg) at 5 m: |z| <= 1.29 m; as an HDL-32E's (down to -30.67 deg)
  // the same ranges would reach 2.55 m below.
  double z_max = 0;
  for (const auto& p : s->points) z_max = std::max(z_max, std::abs(double(p.z)));
  EXPECT_NEAR(z_max, 5.0 * std::sin(15.0 * M_PI / 180), 0.01);
}

TEST(SweepModel, AgreeingByteIsTheSource) {
  const auto s = viewer::sweepOf(vlp16Sweep(40, velodyne::Model::VLP16));
  ASSERT_TRUE(s);
  EXPECT_EQ(s->model, "VLP-16");
  EXPECT_EQ(s->model_source, "product byte");
  EXPECT_EQ(s->model_warning, "");
}

TEST(SweepModel, InconclusivePacketsFallBackToTheStoredCalibration) {
  // One packet, every range zeroed: no pair of channels and no packet pair to time.
  auto v = vlp16Sweep(1, velodyne::Model::HDL32);
  auto* raw = reinterpret_cast<uint8_t*>(&v.scan_packets[0]);
  for (int b = 0; b < velodyne::kBlocksPerPacket; ++b) std::memset(raw + b * 100 + 4, 0, 96);
  v.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("VLP16");
  const auto s = viewer::sweepOf(v);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->model, "VLP-16");
  EXPECT_EQ(s->model_source, "rawlog calibration");
  v.calibration = mrpt::obs::VelodyneCalibration{};  // none stored: the product byte
  EXPECT_EQ(viewer::sweepOf(v)->model, "HDL-32E");
  EXPECT_EQ(viewer::sweepOf(v)->model_source, "product byte");
}

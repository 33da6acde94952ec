#pragma once
// A spinning VLP-16 in a synthetic world: true firing azimuths/times per the manual's timing, ranges
// from a caller's function, packets from the encoder. Truth is kept beside the packets.
#include <cmath>
#include <functional>
#include <vector>

#include "roadslam/velodyne/calibration.h"
#include "roadslam/velodyne/encoder.h"

namespace roadslam::velodyne::test {

/// Range [m] seen by a beam of azimuth a (clockwise from forward, rad) and elevation w (rad).
using RangeFn = std::function<double(double a, double w)>;

struct SyntheticStream {
  std::vector<DataPacketBytes> packets;
  std::vector<double> stamps_s;  ///< packet (first firing) times [s]
};

/// \p n packets of a VLP-16 spinning at \p rate_hz from azimuth \p az0_deg, timestamps from t0_us.
inline SyntheticStream spinVlp16(const RangeFn& range, int n, double rate_hz = 10.0,
                                 double az0_deg = 0.0, uint32_t t0_us = 1000000,
                                 ReturnMode mode = ReturnMode::Strongest, Model product = Model::VLP16) {
  const Calibration cal = Calibration::builtinVlp16();
  SyntheticStream s;
  const double deg_per_s = 360.0 * rate_hz;
  const int seq_per_packet = mode == ReturnMode::Dual ? 12 : 24;
  for (int k = 0; k < n; ++k) {
    std::array<FiringSequence, kVlp16SequencesPerPacket> seq{};
    const double t_pkt = k * seq_per_packet * kVlp16SequencePeriod_s;
    for (int q = 0; q < seq_per_packet; ++q) {
      const double t_seq = t_pkt + q * kVlp16SequencePeriod_s;
      seq[q].azimuth_deg = std::fmod(az0_deg + deg_per_s * t_seq, 360.0);
      for (int l = 0; l < kVlp16Lasers; ++l) {
        const double az = (az0_deg + deg_per_s * (t_seq + l * kVlp16LaserPeriod_s)) * M_PI / 180;
        const float r = static_cast<float>(range(az, cal.lasers[l].vertical_rad));
        seq[q].strongest[l] = {r, static_cast<uint8_t>(10 + l)};
        seq[q].last[l] = {r, static_cast<uint8_t>(10 + l)};
      }
    }
    s.packets.push_back(encodeVlp16Packet(seq, t0_us + static_cast<uint32_t>(std::lround(t_pkt * 1e6)), mode, product));
    s.stamps_s.push_back(1.7e9 + t_pkt);
  }
  return s;
}

/// \p n packets of an HDL-32E spinning at \p rate_hz (a block every 46.08 us, a laser every 1.152 us,
/// HDL-32E manual 63-9113 appendix E), single return, product byte \p product.
inline SyntheticStream spinHdl32(const RangeFn& range, int n, double rate_hz = 10.0, double az0_deg = 0.0,
                                 uint32_t t0_us = 1000000, Model product = Model::HDL32) {
  const Calibration cal = Calibration::builtinHdl32();
  SyntheticStream s;
  const double deg_per_s = 360.0 * rate_hz;
  for (int k = 0; k < n; ++k) {
    std::array<Hdl32Firing, kBlocksPerPacket> firings{};
    const double t_pkt = k * kBlocksPerPacket * kHdl32BlockPeriod_s;
    for (int b = 0; b < kBlocksPerPacket; ++b) {
      const double t_block = t_pkt + b * kHdl32BlockPeriod_s;
      firings[b].azimuth_deg = std::fmod(az0_deg + deg_per_s * t_block, 360.0);
      for (int c = 0; c < kHdl32Lasers; ++c) {
        const double az = (az0_deg + deg_per_s * (t_block + c * kHdl32LaserPeriod_s)) * M_PI / 180;
        firings[b].returns[c] = {static_cast<float>(range(az, cal.lasers[c].vertical_rad)), static_cast<uint8_t>(c)};
      }
    }
    s.packets.push_back(encodeHdl32Packet(firings, t0_us + static_cast<uint32_t>(std::lround(t_pkt * 1e6)),
                                          ReturnMode::Strongest, product));
    s.stamps_s.push_back(1.7e9 + t_pkt);
  }
  return s;
}

/// Ray from the origin of our lidar frame (x fwd, y left, z up) along azimuth a / elevation w.
inline void beamDirection(double a, double w, double d[3]) {
  d[0] = std::cos(w) * std::cos(a);
  d[1] = -std::cos(w) * std::sin(a);
  d[2] = std::sin(w);
}

/// Axis-aligned closed room around the sensor: first positive hit of the ray [m].
struct BoxRoom {
  double x_min = -4, x_max = 4, y_min = -2.5, y_max = 2.5, z_min = -1.0, z_max = 2.0;
  double range(double a, double w) const {
    double d[3];
    beamDirection(a, w, d);
    const double lo[3] = {x_min, y_min, z_min}, hi[3] = {x_max, y_max, z_max};
    double best = 1e9;
    for (int i = 0; i < 3; ++i) {
      if (std::abs(d[i]) < 1e-12) continue;
      const double t = (d[i] > 0 ? hi[i] : lo[i]) / d[i];
      if (t > 0) best = std::min(best, t);
    }
    return best;
  }
};

}  // namespace roadslam::velodyne::test

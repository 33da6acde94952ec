#include "roadslam/sources/boxroom.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <limits>
#include <stdexcept>

#include "roadslam/common/atomic_file.h"
#include "roadslam/common/param_table.h"
#include "roadslam/pcap/pcap_writer.h"
#include "roadslam/velodyne/encoder.h"

namespace roadslam::sources {
namespace {

using velodyne::kVlp16Lasers;
using velodyne::kVlp16SequencesPerPacket;
using unit::kDeg;
// VLP-16 manual 63-9243, table 9-1: elevation of laser ids 0..15 in firing order [deg].
constexpr std::array<double, kVlp16Lasers> kElevation_deg = {-15, 1, -13, 3, -11, 5, -9, 7,
                                                             -7,  9, -5, 11, -3, 13, -1, 15};
constexpr uint16_t kSensorSrcPort = 2368;
constexpr double kKnots = 0.0;  // static sensor

enum class Surface { Floor, Ceiling, WallX, WallY };

// Ray/box exit: smallest positive distance to the six planes along the beam.
double castRay(const BoxRoomParams& p, double az_deg, double el_deg, Surface* hit) {
  const double ca = std::cos(az_deg * kDeg), sa = std::sin(az_deg * kDeg);
  const double cw = std::cos(el_deg * kDeg), sw = std::sin(el_deg * kDeg);
  const double d[3] = {cw * ca, -cw * sa, sw};
  const double o[3] = {p.sensor_x_m, p.sensor_y_m, p.sensor_z_m};
  const double hi[3] = {p.length_m, p.width_m, p.height_m};
  double best = std::numeric_limits<double>::infinity();
  Surface s = Surface::WallX;
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) < 1e-12) continue;
    const double t = ((d[i] > 0 ? hi[i] : 0.0) - o[i]) / d[i];
    if (t > 0 && t < best) {
      best = t;
      s = i == 0 ? Surface::WallX : i == 1 ? Surface::WallY : d[i] < 0 ? Surface::Floor : Surface::Ceiling;
    }
  }
  if (hit) *hit = s;
  return best;
}

uint8_t intensityOf(Surface s) {
  switch (s) {
    case Surface::Floor: return 40;
    case Surface::Ceiling: return 120;
    case Surface::WallX: return 70;
    case Surface::WallY: return 90;
  }
  return 0;
}

// A $GPRMC sentence for capture time t (NMEA 0183 v2.3, checksum = XOR of the body).
std::string rmcSentence(double t_s) {
  const std::time_t secs = std::time_t(std::floor(t_s));
  std::tm utc{};
  gmtime_r(&secs, &utc);
  char body[96];
  std::snprintf(body, sizeof body, "GPRMC,%02d%02d%02d,A,3649.7480,N,00224.4540,W,%05.1f,000.0,%02d%02d%02d,,,A",
                utc.tm_hour, utc.tm_min, utc.tm_sec, kKnots, utc.tm_mday, utc.tm_mon + 1,
                utc.tm_year % 100);
  uint8_t cs = 0;
  for (const char* c = body; *c; ++c) cs ^= uint8_t(*c);
  char out[112];
  std::snprintf(out, sizeof out, "$%s*%02X\r\n", body, cs);
  return out;
}

uint32_t usPastHour(double t_s) {
  const double past = std::fmod(t_s, 3600.0);
  return uint32_t(std::llround(past * 1e6)) % 3600000000u;
}

}  // namespace

double boxRoomRange(const BoxRoomParams& p, double azimuth_deg, double elevation_deg) {
  return castRay(p, azimuth_deg, elevation_deg, nullptr);
}

BoxRoomSummary writeBoxRoomPcap(const std::string& path, const BoxRoomParams& p) {
  if (p.revolutions < 1 || p.packets_per_revolution < 2)
    throw std::runtime_error("box room: revolutions >= 1 and packets_per_revolution >= 2 required");
  if (std::fmod(p.start_azimuth_deg, 360.0) == 0.0)
    throw std::runtime_error("box room: start_azimuth_deg must lie inside a turn (sweep count oracle)");
  const std::string tmp = tempPathFor(path);
  BoxRoomSummary sum;
  sum.min_range_m = std::numeric_limits<double>::infinity();
  try {
    pcap::PcapWriter out(tmp, path);
    const int seq_per_rev = p.packets_per_revolution * kVlp16SequencesPerPacket;
    const double step_deg = 360.0 / seq_per_rev;  // azimuth advance per firing sequence
    const double packet_s = kVlp16SequencesPerPacket * velodyne::kVlp16SequencePeriod_s;
    const int n_packets = p.revolutions * p.packets_per_revolution;
    const int pos_every = p.position_packets_per_revolution > 0
                              ? std::max(1, p.packets_per_revolution / p.position_packets_per_revolution)
                              : 0;
    for (int k = 0; k < n_packets; ++k) {
      std::array<velodyne::FiringSequence, kVlp16SequencesPerPacket> seq{};
      for (int j = 0; j < kVlp16SequencesPerPacket; ++j) {
        const double az0 = p.start_azimuth_deg + (k * kVlp16SequencesPerPacket + j) * step_deg;
        seq[j].azimuth_deg = std::fmod(az0, 360.0);
        for (int l = 0; l < kVlp16Lasers; ++l) {
          // Manual 9.5: laser l fires l x 2.304 us into the 55.296 us sequence.
          const double az = az0 + step_deg * l * velodyne::kVlp16LaserPeriod_s /
                                      velodyne::kVlp16SequencePeriod_s;
          Surface s;
          const double r = castRay(p, az, kElevation_deg[l], &s);
          seq[j].strongest[l] = {float(r), intensityOf(s)};
          sum.min_range_m = std::min(sum.min_range_m, double(float(r)));
          sum.max_range_m = std::max(sum.max_range_m, double(float(r)));
        }
      }
      const double t_first = p.start_time_s + k * packet_s;
      const auto pkt = velodyne::encodeVlp16Packet(seq, usPastHour(t_first));
      // Captured when the packet leaves the sensor, after its last firing.
      out.writeUdp(t_first + packet_s, kSensorSrcPort, velodyne::kDefaultDataPort, pkt.data(),
                   pkt.size());
      ++sum.data_packets;
      sum.points += kVlp16SequencesPerPacket * kVlp16Lasers;
      if (pos_every > 0 && k % pos_every == 0) {
        const auto pos = velodyne::encodePositionPacket(usPastHour(t_first),
                                                        rmcSentence(t_first).c_str());
        out.writeUdp(t_first + packet_s, kSensorSrcPort, velodyne::kDefaultPositionPort,
                     pos.data(), pos.size());
        ++sum.position_packets;
      }
    }
    out.close();
    sum.duration_s = (n_packets - 1) * packet_s;  // first to last capture stamp
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  // Starting inside a turn: one wrap per revolution, so the complete sweeps are those between the
  // first and the last wrap, plus a partial lead-in and lead-out.
  sum.complete_sweeps = p.revolutions - 1;
  sum.partial_sweeps = 2;
  commitTempFile(tmp, path);
  return sum;
}

}  // namespace roadslam::sources

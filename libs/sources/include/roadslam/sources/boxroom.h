#pragma once
/// \file boxroom.h
/// Generator of the bundled capture rawlogs/boxroom-vlp16.pcap: a static VLP-16 inside a closed
/// box room, rendered by exact ray casting, encoded with libs/velodyne's encoder and written with
/// libs/pcap's PcapWriter. Deterministic (no randomness, fixed start time), so a test can
/// regenerate the file and demand byte identity with the committed one.
///
/// Frames: room frame R with the origin at a floor corner, x along the length, y along the width,
/// z up; the lidar frame L is R translated to the sensor position (no rotation). Beam direction
/// for azimuth a (clockwise seen from above, 0 = +x, as the sensor's rotation) and elevation w:
/// (cos w cos a, -cos w sin a, sin w). Every beam hits a wall, so every firing returns.

#include <cstdint>
#include <string>

namespace roadslam::sources {

struct BoxRoomParams {
  double length_m = 8.0, width_m = 5.0, height_m = 3.0;  ///< room size along x, y, z [m]
  double sensor_x_m = 3.0, sensor_y_m = 2.0;             ///< sensor position in R [m]
  double sensor_z_m = 1.0;                               ///< sensor height above the floor [m]
  int revolutions = 5;               ///< turns recorded, from start_azimuth_deg [count]
  int packets_per_revolution = 76;   ///< 76 x 1327.104 us = 9.915 Hz rotation [count]
  double start_azimuth_deg = 180.0;  ///< inside a turn (not 0): first and last sweeps partial [deg]
  double start_time_s = 1453364282.0;  ///< capture time of the first firing [s since epoch]
  int position_packets_per_revolution = 1;  ///< $GPRMC position packets [count per turn]
};

/// What the generator wrote: the analytic oracle for decoders and for `roadslam-rawlog info`.
struct BoxRoomSummary {
  uint64_t data_packets = 0;      ///< [count]
  uint64_t position_packets = 0;  ///< [count]
  uint64_t points = 0;            ///< returns encoded = firings x 16 (all beams hit) [count]
  int complete_sweeps = 0;        ///< revolutions between the first and last azimuth wrap [count]
  int partial_sweeps = 0;         ///< lead-in and lead-out pieces [count]
  double duration_s = 0;          ///< first to last data packet capture stamp [s]
  double min_range_m = 0, max_range_m = 0;  ///< extreme encoded ranges [m]
};

/// Range along the beam from the sensor to the room's boundary [m] (the ray-casting oracle).
double boxRoomRange(const BoxRoomParams& p, double azimuth_deg, double elevation_deg);

/// Writes the capture to \p path atomically (temporary name, renamed when complete).
/// Throws std::runtime_error naming the path when it cannot be written.
BoxRoomSummary writeBoxRoomPcap(const std::string& path, const BoxRoomParams& params = {});

}  // namespace roadslam::sources

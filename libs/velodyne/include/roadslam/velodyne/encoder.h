#pragma once
/// \file encoder.h
/// The inverse of the decoder: builds real 1206-byte VLP-16 and HDL-32E data packets from firings.
/// Used by the simulator and by round-trip tests (encode known points, decode, compare within the
/// packet quantisation: 2 mm range, 0.01 deg azimuth).

#include <array>
#include <cstdint>

#include "roadslam/velodyne/packet.h"

namespace roadslam::velodyne {

/// One laser's return in a firing sequence. range_m <= 0 (or beyond 131 m) encodes "no return" (0).
struct LaserReturn {
  float range_m = 0;      ///< raw range along the beam [m], before any calibration distance offset
  uint8_t intensity = 0;  ///< calibrated reflectivity 0..255
};

/// One VLP-16 firing sequence: 16 lasers in firing order (laser id 0..15 = packet channel order,
/// elevations -15, 1, -13, 3, ... deg), azimuth at the sequence's first firing.
struct FiringSequence {
  double azimuth_deg = 0;                         ///< [0, 360)
  std::array<LaserReturn, kVlp16Lasers> strongest;
  std::array<LaserReturn, kVlp16Lasers> last;     ///< used only in ReturnMode::Last / Dual
};

/// Encodes 24 firing sequences (one packet's worth, 1.327 ms) into a data packet.
/// Strongest/Last: sequence 2k and 2k+1 go into block k; the block azimuth is that of sequence 2k
/// (the second sequence's azimuth is implied, as in the real sensor).
/// Dual: 12 sequences fill 6 block pairs sharing one azimuth, block 2j = last returns, block 2j+1 =
/// strongest (VLP-16 manual 9.3.2.2); sequences 12..23 ignored.
/// \param timestamp_us microseconds past the top of the hour of the first firing.
DataPacketBytes encodeVlp16Packet(const std::array<FiringSequence, kVlp16SequencesPerPacket>& seq,
                                  uint32_t timestamp_us, ReturnMode mode = ReturnMode::Strongest,
                                  Model product = Model::VLP16);

/// One HDL-32E firing: 32 lasers in packet channel order (HDL-32E manual 63-9113 appendix E:
/// elevations -30.67, -9.33, -29.33, -8.00, ... deg), azimuth at the firing's first laser.
struct Hdl32Firing {
  double azimuth_deg = 0;                      ///< [0, 360)
  std::array<LaserReturn, kHdl32Lasers> returns;
};

/// Encodes 12 HDL-32E firings (one packet, 552.96 us: a block every 46.08 us) into a data packet,
/// firing k into block k, single return (\p mode Strongest or Last; the byte is written as given).
DataPacketBytes encodeHdl32Packet(const std::array<Hdl32Firing, kBlocksPerPacket>& firings, uint32_t timestamp_us,
                                  ReturnMode mode = ReturnMode::Strongest, Model product = Model::HDL32);

/// A 512-byte position packet carrying \p nmea (e.g. a $GPRMC sentence) and the timestamp.
std::array<uint8_t, kPositionPacketSize> encodePositionPacket(uint32_t timestamp_us,
                                                              const char* nmea);

}  // namespace roadslam::velodyne

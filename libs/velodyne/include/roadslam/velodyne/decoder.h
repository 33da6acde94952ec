#pragma once
/// \file decoder.h
/// Decodes Velodyne VLP-16 / HDL-32E data packets (1206-byte UDP payloads, packet.h) into points of
/// our lidar frame: x forward (azimuth 0), y left, z up, metres; see calibration.h for the model
/// and the mapping to VeloView's frame (x right, y forward, z up).
///
/// Unlike MRPT's CObservationVelodyneScan::generatePointCloud, both 16-laser firing sequences of
/// every VLP-16 block are decoded. Per point: firing time (VLP-16 manual 9.5: 2.304 us per laser,
/// 55.296 us per sequence; HDL-32E: 1.152 us per laser, 46.08 us per block), azimuth interpolated
/// within the block from the packet's block-to-block rate (as VeloView does), ring, intensity.
/// Zero distance means "no return" and gives no point.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/velodyne/calibration.h"
#include "roadslam/velodyne/decoder_params.h"
#include "roadslam/velodyne/packet.h"

namespace roadslam::velodyne {

enum class DecodeStatus : uint8_t {
  Ok,
  WrongSize,           ///< payload is not 1206 bytes (e.g. a 512-byte position packet)
  BadBlockFlag,        ///< a block does not start with 0xEEFF (HDL-64 upper block, corruption)
  UnknownModel,        ///< product byte not VLP-16/HDL-32E and no model forced in DecoderParams
};
constexpr int kDecodeStatusCount = 4;
const char* toString(DecodeStatus status);

/// Where each block's points start in the output buffer, and when the block fired.
struct PacketInfo {
  Model model = Model::Unknown;
  ReturnMode mode = ReturnMode::Strongest;   ///< 0x39 = dual; any other byte decodes as single
  uint32_t timestamp_us = 0;                 ///< sensor time of the first firing [us past the hour]
  std::array<uint16_t, kBlocksPerPacket> block_azimuth{};  ///< raw block azimuth [0.01 deg]
  std::array<uint32_t, kBlocksPerPacket> block_first_point{};  ///< index into the output buffer
  std::array<float, kBlocksPerPacket> block_time_s{};  ///< first firing of the block after timestamp [s]
  uint32_t end_point = 0;                    ///< one past the packet's last point in the buffer
};

class Decoder {
 public:
  /// Built-in calibration tables, or params.calibration_file (throws naming the file if bad).
  explicit Decoder(const DecoderParams& params = {});
  /// Uses \p calibration for its model, built-in tables for the other.
  Decoder(const DecoderParams& params, const Calibration& calibration);

  /// Decodes one data packet and appends its points to \p out (no allocation once \p out has the
  /// capacity; a packet gives at most 384 points). ScanPoint::t is relative to the packet's
  /// timestamp (first firing) [s]. On any status but Ok nothing is appended.
  DecodeStatus decode(const uint8_t* data, std::size_t size, std::vector<ScanPoint>& out,
                      PacketInfo* info = nullptr) const noexcept;

  /// Model the decoder will use for this packet: the forced one (DecoderParams::model), else the
  /// stream's (setStreamModel) when the product byte names a model we decode, else the product byte.
  Model modelOf(const uint8_t* data, std::size_t size) const noexcept;
  /// The model chosen for the whole stream (model_choice.h: the packet layout over a product byte
  /// that disagrees); Unknown (the default) = each packet's product byte. Ignored when a model is forced.
  void setStreamModel(Model model) { stream_model_ = model; }
  const Calibration& calibration(Model model) const;
  const DecoderParams& params() const { return params_; }

 private:
  DecoderParams params_;
  Model stream_model_ = Model::Unknown;
  Calibration vlp16_, hdl32_;
};

/// Sensor-time duration of one data packet [s] (VLP-16 1.327104 ms, HDL-32E 0.55296 ms).
double packetDuration_s(Model model);

}  // namespace roadslam::velodyne

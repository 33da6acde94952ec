#pragma once
/// \file decoder_params.h
/// Settings of the Velodyne decoder and sweep assembler, loaded from an ini section:
/// \code
/// [velodyne]
/// model             = auto     ; auto (product byte) | vlp16 | hdl32 (forces the model)
/// calibration_file  =          ; VeloView/Velodyne db.xml; empty = built-in manual table
/// min_range_m       = 0.0      ; returns closer than this are dropped [m] (0 = keep all non-zero)
/// max_range_m       = 131.0    ; returns farther than this are dropped [m]
/// dual_returns      = both     ; both | strongest | last (which returns of a dual-mode packet)
/// drop_dual_duplicates = true  ; drop the second return when equal to the first (as VeloView)
/// intra_block_azimuth  = true  ; interpolate each laser's azimuth within a block (as VeloView)
/// cut_azimuth_deg   = 0.0      ; a sweep ends when the block azimuth crosses this angle [deg]
/// stamp_source      = capture  ; capture (pcap/receive clock) | sensor (top-of-hour timestamp)
/// \endcode

#include <string>

#include "roadslam/velodyne/packet.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace roadslam {
class ParamTable;
}

namespace roadslam::velodyne {

enum class DualReturns { Both, Strongest, Last };
enum class StampSource { Capture, Sensor };

struct DecoderParams {
  Model model = Model::Unknown;      ///< Unknown = detect from the product byte
  std::string calibration_file;      ///< VeloView XML path; empty = built-in table
  double min_range_m = 0.0;          ///< [m]
  double max_range_m = 131.0;        ///< [m]
  DualReturns dual_returns = DualReturns::Both;
  bool drop_dual_duplicates = true;
  bool intra_block_azimuth = true;
  double cut_azimuth_rad = 0.0;      ///< [rad], ini key cut_azimuth_deg
  StampSource stamp_source = StampSource::Capture;

  /// The ini keys, one line each (common/param_table.h): load, save and the known keys.
  void fields(ParamTable& t);
  /// Throws std::runtime_error naming section/key on malformed or unknown values.
  void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& section);
  void saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& section) const;
};

/// "auto" / "vlp16" / "hdl32" <-> Model; parseModel throws std::invalid_argument on other text.
Model parseModel(const std::string& text);
std::string modelName(Model model);

}  // namespace roadslam::velodyne

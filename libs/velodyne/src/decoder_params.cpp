#include "roadslam/velodyne/decoder_params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"

namespace roadslam::velodyne {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

[[noreturn]] void badValue(const std::string& section, const std::string& key,
                           const std::string& value) {
  throw std::runtime_error("[" + section + "] " + key + ": invalid value '" + value + "'");
}

}  // namespace

Model parseModel(const std::string& text) {
  if (text == "auto" || text.empty()) return Model::Unknown;
  if (text == "vlp16" || text == "VLP16" || text == "VLP-16") return Model::VLP16;
  if (text == "hdl32" || text == "HDL32" || text == "HDL-32E") return Model::HDL32;
  throw std::invalid_argument("unknown Velodyne model '" + text + "' (auto, vlp16, hdl32)");
}

std::string modelName(Model model) {
  switch (model) {
    case Model::VLP16: return "vlp16";
    case Model::HDL32: return "hdl32";
    default: return "auto";
  }
}

void DecoderParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                       const std::string& section) {
  const std::string m = readString(cfg, section, "model", modelName(model));
  try {
    model = parseModel(m);
  } catch (const std::invalid_argument&) {
    badValue(section, "model", m);
  }
  calibration_file = readString(cfg, section, "calibration_file", calibration_file);
  min_range_m = readDouble(cfg, section, "min_range_m", min_range_m);
  max_range_m = readDouble(cfg, section, "max_range_m", max_range_m);
  if (!(min_range_m >= 0) || !(max_range_m > min_range_m))
    badValue(section, "min_range_m/max_range_m",
             std::to_string(min_range_m) + "/" + std::to_string(max_range_m));
  const std::string d = readString(cfg, section, "dual_returns", "both");
  if (d == "both") dual_returns = DualReturns::Both;
  else if (d == "strongest") dual_returns = DualReturns::Strongest;
  else if (d == "last") dual_returns = DualReturns::Last;
  else badValue(section, "dual_returns", d);
  drop_dual_duplicates = readBool(cfg, section, "drop_dual_duplicates", drop_dual_duplicates);
  intra_block_azimuth = readBool(cfg, section, "intra_block_azimuth", intra_block_azimuth);
  cut_azimuth_rad =
      readDouble(cfg, section, "cut_azimuth_deg", cut_azimuth_rad / kDegToRad) * kDegToRad;
  const std::string s = readString(cfg, section, "stamp_source", "capture");
  if (s == "capture") stamp_source = StampSource::Capture;
  else if (s == "sensor") stamp_source = StampSource::Sensor;
  else badValue(section, "stamp_source", s);
}

void DecoderParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                     const std::string& section) const {
  cfg.write(section, "model", modelName(model));
  cfg.write(section, "calibration_file", calibration_file);
  cfg.write(section, "min_range_m", min_range_m);
  cfg.write(section, "max_range_m", max_range_m);
  cfg.write(section, "dual_returns",
            std::string(dual_returns == DualReturns::Both        ? "both"
                        : dual_returns == DualReturns::Strongest ? "strongest"
                                                                 : "last"));
  cfg.write(section, "drop_dual_duplicates", drop_dual_duplicates);
  cfg.write(section, "intra_block_azimuth", intra_block_azimuth);
  cfg.write(section, "cut_azimuth_deg", cut_azimuth_rad / kDegToRad);
  cfg.write(section, "stamp_source",
            std::string(stamp_source == StampSource::Capture ? "capture" : "sensor"));
}

}  // namespace roadslam::velodyne

#include "roadslam/velodyne/decoder_params.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::velodyne {
namespace {

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

namespace {
const NameTable<DualReturns>& dualReturnsNames() {
  static const NameTable<DualReturns> t{
      {DualReturns::Both, "both"}, {DualReturns::Strongest, "strongest"}, {DualReturns::Last, "last"}};
  return t;
}
const NameTable<StampSource>& stampSourceNames() {
  static const NameTable<StampSource> t{{StampSource::Capture, "capture"}, {StampSource::Sensor, "sensor"}};
  return t;
}
}  // namespace

// `model` (first key, with the aliases parseModel accepts) is read and written by hand beside the table.
void DecoderParams::fields(ParamTable& t) {
  t.text("calibration_file", calibration_file);
  t.num("min_range_m", min_range_m);
  t.num("max_range_m", max_range_m);
  t.choice("dual_returns", dual_returns, dualReturnsNames());
  t.flag("drop_dual_duplicates", drop_dual_duplicates);
  t.flag("intra_block_azimuth", intra_block_azimuth);
  t.angle("cut_azimuth_deg", cut_azimuth_rad);
  t.choice("stamp_source", stamp_source, stampSourceNames());
}

void DecoderParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                       const std::string& section) {
  const std::string m = readString(cfg, section, "model", modelName(model));
  try {
    model = parseModel(m);
  } catch (const std::invalid_argument&) {
    badValue(section, "model", m);
  }
  loadFields(*this, cfg, section);
  if (!(min_range_m >= 0) || !(max_range_m > min_range_m))
    badValue(section, "min_range_m/max_range_m",
             std::to_string(min_range_m) + "/" + std::to_string(max_range_m));
}

void DecoderParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                     const std::string& section) const {
  cfg.write(section, "model", modelName(model));
  saveFields(*this, cfg, section);
}

}  // namespace roadslam::velodyne

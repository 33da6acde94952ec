#include "roadslam/velodyne/model_choice.h"

#include <cstdio>

#include "roadslam/velodyne/decoder_params.h"

namespace roadslam::velodyne {
namespace {

Model modelOfByte(int product_byte) {
  if (product_byte == static_cast<int>(Model::VLP16)) return Model::VLP16;
  if (product_byte == static_cast<int>(Model::HDL32)) return Model::HDL32;
  return Model::Unknown;
}

std::string hexByte(int byte) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02X", byte & 0xFF);
  return text;
}

/// "[velodyne] model = hdl32" or "--model hdl32".
std::string setting(const std::string& how, Model model) {
  const bool ini = how.find('[') != std::string::npos;
  return how + (ini ? " = " : " ") + modelName(model);
}

}  // namespace

const char* toString(ModelSource source) {
  switch (source) {
    case ModelSource::Ini: return "ini";
    case ModelSource::PacketLayout: return "packet layout";
    case ModelSource::ProductByte: return "product byte";
  }
  return "?";
}

ModelChoice chooseModel(Model forced, const LayoutVerdict& layout, const std::string& force_setting) {
  ModelChoice c;
  c.layout = layout;
  const Model seen = layout.model;
  if (forced != Model::Unknown) {
    c.model = forced;
    c.source = ModelSource::Ini;
    if (seen != Model::Unknown && seen != forced)
      c.warning = "packets have the " + layout.describe() + " but " + setting(force_setting, forced) + " forces " +
                  displayName(forced) + "; decoding as " + displayName(forced) + " as set";
    return c;
  }
  if (layout.packets == 0) return c;  // nothing to decode
  const Model byte = modelOfByte(layout.product_byte);
  if (byte == Model::Unknown) {
    c.warning = "product byte " + hexByte(layout.product_byte) + " is neither VLP-16 (0x22) nor HDL-32E (0x21): "
                "the data packets are not decoded";
    if (seen != Model::Unknown)
      c.warning += "; they have the " + layout.describe() + ": set " + setting(force_setting, seen) + " to decode them";
    return c;
  }
  if (seen == Model::Unknown || seen == byte) {
    c.model = byte;
    return c;
  }
  c.model = seen;
  c.source = ModelSource::PacketLayout;
  c.warning = "packets have the " + layout.describe() + " but product byte " + hexByte(layout.product_byte) +
              " says " + displayName(byte) + "; decoding as " + displayName(seen) + "; set " +
              setting(force_setting, byte) + " to force";
  return c;
}

}  // namespace roadslam::velodyne

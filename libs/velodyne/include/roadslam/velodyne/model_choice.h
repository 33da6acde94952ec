#pragma once
/// \file model_choice.h
/// Which model a stream of data packets is decoded as, and why: the one rule every program that
/// decodes Velodyne packets follows (docs/velodyne-decoder.md, "Which model").
///
/// - A model set by the user (ini `[velodyne] model`, `--model`) is obeyed; when the packets' layout
///   (layout.h) says otherwise, a warning names both.
/// - `auto`: the packet layout is physical evidence and the product byte a label some firmware gets
///   wrong, so where they disagree the layout wins, with a warning naming both and how to force the
///   byte's model. Where the layout is inconclusive, the product byte decides. A product byte that
///   is neither VLP-16 (0x22) nor HDL-32E (0x21) is not decoded (another sensor's table would give
///   wrong points), with a warning.

#include <string>

#include "roadslam/velodyne/layout.h"

namespace roadslam::velodyne {

enum class ModelSource { Ini, PacketLayout, ProductByte };
/// "ini", "packet layout", "product byte": summary.json's lidar_model_source values.
const char* toString(ModelSource source);

struct ModelChoice {
  Model model = Model::Unknown;  ///< the model decoded; Unknown: the packets are not decoded
  ModelSource source = ModelSource::ProductByte;
  LayoutVerdict layout;          ///< what the layout check found
  std::string warning;           ///< non-empty when the layout disagrees with the byte or the set model
};

/// Applies the rule above. \p forced: the model the user set (Unknown = auto). \p force_setting:
/// how the user sets it, for the warning's advice, e.g. "[velodyne] model" or "--model".
ModelChoice chooseModel(Model forced, const LayoutVerdict& layout,
                        const std::string& force_setting = "[velodyne] model");

}  // namespace roadslam::velodyne

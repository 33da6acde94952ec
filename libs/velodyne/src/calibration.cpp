#include "roadslam/velodyne/calibration.h"

#include <mrpt/obs/VelodyneCalibration.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace roadslam::velodyne {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

Calibration fromVerticalTable(Model model, const double* vertical_deg, int n) {
  Calibration c;
  c.model = model;
  c.lasers.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) c.lasers[static_cast<std::size_t>(i)].vertical_rad = vertical_deg[i] * kDegToRad;
  c.finalize();
  return c;
}

}  // namespace

int laserCount(Model model) {
  switch (model) {
    case Model::VLP16: return 16;
    case Model::HDL32: return 32;
    default: return 0;
  }
}

Calibration Calibration::builtinVlp16() {
  // VLP-16 user manual 63-9243, table 9-1 (laser ID -> vertical angle).
  static constexpr double kVertical[16] = {-15, 1, -13, 3, -11, 5, -9, 7,
                                           -7,  9, -5,  11, -3, 13, -1, 15};
  return fromVerticalTable(Model::VLP16, kVertical, 16);
}

Calibration Calibration::builtinHdl32() {
  // HDL-32E user manual 63-9113, laser firing order / vertical angle table.
  static constexpr double kVertical[32] = {
      -30.67, -9.33,  -29.33, -8.00,  -28.00, -6.67,  -26.67, -5.33,  -25.33, -4.00, -24.00,
      -2.67,  -22.67, -1.33,  -21.33, 0.00,   -20.00, 1.33,   -18.67, 2.67,   -17.33, 4.00,
      -16.00, 5.33,   -14.67, 6.67,   -13.33, 8.00,   -12.00, 9.33,   -10.67, 10.67};
  return fromVerticalTable(Model::HDL32, kVertical, 32);
}

Calibration Calibration::builtin(Model model) {
  switch (model) {
    case Model::VLP16: return builtinVlp16();
    case Model::HDL32: return builtinHdl32();
    default: throw std::invalid_argument("Calibration::builtin: unknown Velodyne model");
  }
}

Calibration Calibration::fromXmlFile(const std::string& path) {
  mrpt::obs::VelodyneCalibration mc;
  if (!mc.loadFromXMLFile(path))
    throw std::runtime_error("Velodyne calibration: cannot load XML '" + path + "'");
  Calibration c;
  const std::size_t n = mc.laser_corrections.size();
  c.model = n == 16 ? Model::VLP16 : n == 32 ? Model::HDL32 : Model::Unknown;
  if (c.model == Model::Unknown)
    throw std::runtime_error("Velodyne calibration '" + path + "': " + std::to_string(n) +
                             " enabled lasers, expected 16 (VLP-16) or 32 (HDL-32E)");
  c.lasers.resize(n);
  // MRPT keeps angles in degrees and converts the XML's centimetres to metres.
  for (std::size_t i = 0; i < n; ++i) {
    const auto& m = mc.laser_corrections[i];
    auto& l = c.lasers[i];
    l.vertical_rad = m.verticalCorrection * kDegToRad;
    l.azimuth_correction_rad = m.azimuthCorrection * kDegToRad;
    l.distance_correction_m = m.distanceCorrection;
    l.vertical_offset_m = m.verticalOffsetCorrection;
    l.horizontal_offset_m = m.horizontalOffsetCorrection;
  }
  c.finalize();
  return c;
}

void Calibration::finalize() {
  std::vector<std::size_t> order(lasers.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return lasers[a].vertical_rad < lasers[b].vertical_rad;
  });
  for (std::size_t r = 0; r < order.size(); ++r) lasers[order[r]].ring = static_cast<uint16_t>(r);
  for (auto& l : lasers) {
    l.sin_vert = std::sin(l.vertical_rad);
    l.cos_vert = std::cos(l.vertical_rad);
    l.sin_azc = std::sin(l.azimuth_correction_rad);
    l.cos_azc = std::cos(l.azimuth_correction_rad);
  }
}

}  // namespace roadslam::velodyne

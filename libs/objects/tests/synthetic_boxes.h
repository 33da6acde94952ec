#pragma once
// A VLP-16-like sweep ray-cast against a flat road and upright boxes with known poses: the oracle
// of the segmentation tests and the benchmark (independent of the simulator).
#include <vector>

#include "roadslam/common/scan.h"
#include "roadslam/preprocess/ground_segmentation.h"

namespace roadslam::objects::test {

struct SynthBox {
  double cx, cy, yaw, length, width, height;  ///< centre on the road, yaw of the length axis [m, rad]
};

/// 16 rings from -15 to +15 deg, \p azimuth_steps firings per turn, lidar \p sensor_height_m above a
/// flat road, returns up to 100 m; boxes stand on the road.
Scan castSweep(const std::vector<SynthBox>& boxes, int azimuth_steps = 1800, double sensor_height_m = 1.9);

/// A street: parked and moving cars on both sides (8 boxes).
std::vector<SynthBox> streetScene();

/// The street cast into one sweep with its ground labels (ClusterParams' defaults), made once: the
/// benchmarks' input.
struct LabelledSweep {
  Scan scan;
  preprocess::GroundLabels g;
};
const LabelledSweep& streetSweep();

}  // namespace roadslam::objects::test

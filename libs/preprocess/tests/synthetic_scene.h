#pragma once
// Test/bench fixture: a VLP-16-like sweep ray-cast into a street with known labels: a road that
// climbs (slope changes at a crest), 0.15 m curbs, raised sidewalks, building walls and a car-sized
// box. Analytic ray casting, fixed-seed range noise.

#include "roadslam/common/scan.h"

#include <cstdint>
#include <vector>

namespace roadslam::preprocess::fixtures {

struct StreetScene {
  double sensor_height_m = 1.8;   // lidar above the road at x = 0 [m]
  double slope_near = 0.06;       // road dz/dx for x < crest_x_m [-]
  double slope_far = 0.14;        // road dz/dx beyond the crest [-]
  double crest_x_m = 15.0;        // where the slope changes [m]
  double slope_lateral = 0.0;     // road dz/dy (cross slope) [-]
  double road_half_width_m = 4.0; // curb position |y| [m]
  double curb_height_m = 0.15;    // [m]
  double wall_y_m = 8.0;          // building walls at |y| [m]
  double wall_height_m = 6.0;     // [m]
  bool with_box = true;           // a 4 x 2 x 1.5 m box on the road at x = 8..12
  double range_noise_m = 0.01;    // 1-sigma range noise [m]
  int azimuth_steps = 1800;       // VLP-16 at 10 Hz: 0.2 deg [-]
  uint64_t seed = 7;
};

struct LabelledScan {
  Scan scan;
  std::vector<uint8_t> ground;  // 1 = road or sidewalk surface, 0 = curb face, wall, box
};

/// Height of the road (|y| < road_half_width_m) or sidewalk surface at (x, y) [m, lidar frame].
double terrainZ(const StreetScene& scene, double x, double y);

/// VLP-16 geometry: 16 beams from -15 to +15 deg every 2 deg, max range 100 m.
LabelledScan makeStreetSweep(const StreetScene& scene);

}  // namespace roadslam::preprocess::fixtures

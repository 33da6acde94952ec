#pragma once
// Synthetic scenes for registration tests: surfaces sampled at a given density with a fixed seed.

#include <roadslam/registration/point_cloud.h>

#include <Eigen/Geometry>
#include <cstdint>

namespace roadslam::registration::test {

/// Structured outdoor scene in its own frame: ground, four boxes, three poles, a facade [m].
/// \param density_per_m2 surface sampling density; \param noise_m Gaussian noise sigma.
PointCloud structuredScene(double density_per_m2, double noise_m, uint32_t seed);

/// Corridor along x: floor z=0 and walls y=+-2 m, x in [-30, 30] m: x translation is unobservable.
PointCloud corridorScene(double density_per_m2, double noise_m, uint32_t seed);

/// Every point of \p pts moved by \p T.
PointCloud transformed(const PointCloud& pts, const Eigen::Isometry3d& T);

}  // namespace roadslam::registration::test

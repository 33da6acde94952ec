#pragma once
/// \file robust_kernel.h
/// IRLS weights of the robust kernels (Black & Rangarajan 1996), shared by the registration
/// library and the odometry's voxel-map matcher and gravity prior.
#include <cmath>

#include "roadslam/registration/params.h"

namespace roadslam::registration {

/// Geman-McClure weight w = s^4 / (s^2 + r^2)^2 from the squared residual \p r2 and squared scale \p s2.
inline double gemanMcClureWeight(double r2, double s2) {
  const double d = s2 + r2;
  return s2 * s2 / (d * d);
}

/// Robust kernel weight w(r) for IRLS, w(0) = 1; \p s is the kernel scale.
inline double kernelWeight(Kernel k, double r, double s) {
  switch (k) {
    case Kernel::None: return 1.0;
    case Kernel::Huber: return std::abs(r) <= s ? 1.0 : s / std::abs(r);
    case Kernel::Tukey: {
      if (std::abs(r) > s) return 0.0;
      const double u = 1.0 - (r * r) / (s * s);
      return u * u;
    }
    case Kernel::GemanMcClure: return gemanMcClureWeight(r * r, s * s);
  }
  return 1.0;
}

}  // namespace roadslam::registration

#pragma once
// An angle wrapped to [-pi, pi] (the tracker's headings, the CTRV state's psi).

#include <cmath>

namespace roadslam::objects::detail {

inline double wrapPi(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace roadslam::objects::detail

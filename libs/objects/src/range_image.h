#pragma once
// The range-image column convention the objects share (segmentation's components, the free-space
// history): azimuth atan2(y, x) + pi over [0, 2 pi] in \p bins columns, atan2 taken in the precision
// of \p x and \p y (the segmentation's float points, the free-space history's doubles).
#include <algorithm>
#include <cmath>

namespace roadslam::objects::detail {

template <class T>
int azimuthColumn(T x, T y, int bins) {
  const double az = std::atan2(y, x) + M_PI;  // [0, 2 pi]
  return std::min(bins - 1, static_cast<int>(az / (2 * M_PI) * bins));
}

}  // namespace roadslam::objects::detail

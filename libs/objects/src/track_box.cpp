#include "roadslam/objects/track_box.h"

#include <algorithm>

namespace roadslam::objects {

OrientedBox movingTrackBox(const Track& t, const TrackerParams& p, double lengthen_s) {
  OrientedBox b = t.box();
  b.length_m = std::max(t.length, p.car_length_m) + 2 * t.speed() * lengthen_s;
  b.width_m = std::max(t.width, p.car_width_m);
  return b;
}

}  // namespace roadslam::objects

#pragma once
/// \file track_box.h
/// The box that holds a moving track's points, the one place it is made: for the maps (the objects
/// stage's moving_boxes and retro boxes) and for the odometry's map (the pipeline's exclusion boxes).

#include "roadslam/common/oriented_box.h"
#include "roadslam/objects/params.h"
#include "roadslam/objects/tracker.h"

namespace roadslam::objects {

/// Track \p t's box at its state (map frame: Track::box(), centred on its filtered position), at least
/// a car's size (\p p car_length_m x car_width_m, the parts of the car its detections missed), and
/// lengthened at each end by the distance it drives in \p lengthen_s at its speed: a sweep finds its
/// points up to that long before or after the state's time.
OrientedBox movingTrackBox(const Track& t, const TrackerParams& p, double lengthen_s);

}  // namespace roadslam::objects

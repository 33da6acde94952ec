#pragma once
/// \file objects_layer.h
/// The objects the viewer draws over a replay: the confirmed tracks of each sweep (their boxes, ids
/// and velocity arrows, moving and static in their own colours) and the objects no track took, from
/// a `roadslam-map` folder's tracks.csv and objects.csv (formats: libs/objects/include/roadslam/objects/stage.h)
/// or, with `--run-slam` and `[objects] enabled`, from the objects stage as it runs. Map frame [m].

#include <string>
#include <vector>

#include "roadslam/common/oriented_box.h"

namespace mrpt::opengl {
class COpenGLScene;
}

namespace roadslam::viewer {

/// One box of one sweep, map frame.
struct ObjectBox {
  int track_id = -1;             ///< the confirmed track; -1: an object no confirmed track took
  bool moving = false;           ///< the track is labelled moving
  OrientedBox box;               ///< [m, rad]
  double vx_mps = 0, vy_mps = 0; ///< the track's velocity (0 for untracked objects) [m/s]
};

/// The boxes of one sweep, at the tracks' time (the sweep's pose time, as trajectory.tum's).
struct ObjectBoxes {
  double stamp_s = 0;  ///< [s]
  std::vector<ObjectBox> boxes;
};

/// tracks.csv and objects.csv of the map folder \p dir (rows with track_id -1 only: the others are
/// the tracks' own detections), one ObjectBoxes per stamp, in time order. No tracks.csv: empty.
/// Throws std::runtime_error naming the file and line of a malformed row.
std::vector<ObjectBoxes> readObjectsFolder(const std::string& dir);

/// Inserts into \p scene the boxes of \p f (wire frames from z_min to z_max), each confirmed track's id
/// above it and, moving faster than 0.5 m/s, an arrow to where its velocity takes it in 1 s.
void addObjectBoxes(const ObjectBoxes& f, mrpt::opengl::COpenGLScene& scene);

}  // namespace roadslam::viewer

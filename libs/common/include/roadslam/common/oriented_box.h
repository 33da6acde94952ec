#pragma once
/// \file oriented_box.h
/// An object's box: a rectangle in the x-y plane turned by its yaw, over a range of heights. The one
/// type for every object box: the segmentation's L-shape boxes, the tracks', the boxes that keep
/// moving objects out of the maps and the odometry's map, the top view's and the viewer's, the rows of
/// objects.csv and tracks.csv. The frame is the holder's (lidar, map or world); metres and radians.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

namespace roadslam {

struct OrientedBox {
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();  ///< centre in the x-y plane [m]
  double yaw_rad = 0;                ///< direction of the length axis, from x towards y [rad]
  double length_m = 0, width_m = 0;  ///< full extents along the length axis and across it [m]
  double z_min_m = 0, z_max_m = 0;   ///< range of heights [m]

  /// Whether \p p lies inside the box grown by \p margin_m on every side (x-y and z); a point on a
  /// face is inside. Equals grown(margin_m).contains(p) to the last bit.
  bool contains(const Eigen::Vector3d& p, double margin_m = 0) const;
  /// The box grown by \p margin_m on every side: 2 margin_m longer and wider, margin_m lower and
  /// higher (a negative margin shrinks it).
  OrientedBox grown(double margin_m) const;
  /// The x-y corners, clockwise seen from above (z up): front left, front right, rear right, rear
  /// left ("front": along the yaw; "left": 90 deg counter-clockwise from it).
  std::array<Eigen::Vector2d, 4> corners() const;
  /// The box in another frame, for a pose that is near level (a vehicle's): the centre through the
  /// whole pose \p T_to_from, the yaw turned by the pose's heading (wrapped to [-pi, pi]), the heights
  /// shifted by its z.
  OrientedBox placed(const Eigen::Isometry3d& T_to_from) const;
};

}  // namespace roadslam

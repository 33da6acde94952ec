#pragma once
/// \file deskew.h
/// Motion compensation of a sweep: each point, fired at time t after the sweep start, is moved into
/// the lidar frame at the sweep start assuming constant velocity over the sweep (KISS-ICP, Vizzo et
/// al. 2023, Sec. III-A, eq. 1-2: the motion of the previous frame interpolated by t / dt).

#include <Eigen/Geometry>
#include <vector>

#include "roadslam/common/scan.h"

namespace roadslam::odometry {

/// \param delta_T_start_end lidar motion over \p sweep_duration_s (pose at the end of the sweep in the
///        frame at its start, T_start_end); \param sweep_duration_s [s];
/// \param reference_fraction the points are expressed in the lidar frame at
///        stamp + reference_fraction * sweep_duration_s (0 = sweep start, 0.5 = mid-sweep).
/// Points keep their order; ScanPoint::t is the time after scan.stamp_s [s].
/// Why mid-sweep by default: a velocity error dv in the deskew shifts a start-referenced cloud by
/// about dv * dt / 2, which the registration takes for motion and feeds back into the next
/// prediction (an oscillation at the Nyquist rate of the frame loop); referenced to the middle, the
/// same error only stretches the cloud symmetrically (KISS-ICP deskews to the middle too).
std::vector<Eigen::Vector3d> deskew(const Scan& scan, const Eigen::Isometry3d& delta_T_start_end,
                                    double sweep_duration_s, double reference_fraction = 0.0);

/// Deskews \p scan in place between two known poses (a given trajectory, or the odometry's poses
/// around a sweep): every point, fired at scan.stamp_s + t, moves into the lidar frame at the
/// reference pose \p T_map_ref: p_ref = T_map_ref^-1 T_map_lidar(t) p, with T_map_lidar(t)
/// interpolated (slerp) between \p T_map_start (t = 0) and \p T_map_end (t = \p duration_s).
/// Rings and times are kept; a sweep without point times is left as it is.
void deskewBetween(Scan& scan, const Eigen::Isometry3d& T_map_start, const Eigen::Isometry3d& T_map_end,
                   double duration_s, const Eigen::Isometry3d& T_map_ref);

}  // namespace roadslam::odometry

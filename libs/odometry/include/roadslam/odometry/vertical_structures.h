#pragma once
/// \file vertical_structures.h
/// Gravity from the scene: building walls, poles and tree trunks stand vertical, so their surface
/// normals are horizontal and their axes vertical. A sweep's non-ground points are cut into voxels;
/// planar voxels whose normal is near-horizontal (walls) and linear voxels whose axis is
/// near-vertical (poles, trunks, wall edges) each give constraints n . g = 0 on the up direction g
/// (a line of direction d gives two: both normals of d). Their least-squares g is the eigenvector
/// of the smallest eigenvalue of sum_i w_i n_i n_i^T.
///
/// Why: a 16-beam sensor sees the road as a few rings, so pitch and roll of scan-to-map odometry
/// random-walk (about 2 deg per km on the simulated urban loop, which climbs 11 m in 1 km). These
/// constraints give the odometry an absolute tilt reference, as an accelerometer does for an IMU
/// (used as a prior in the voxel-map registration: registration/src/voxel_map_align.cpp).
/// Frames: lidar frame of the sweep, metres; directions are unit vectors.

#include <cmath>
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "roadslam/registration/gaussian_voxel_map.h"

namespace roadslam::odometry {

/// One constraint n . g_lidar = 0 on the up direction in the lidar frame: the registration's type,
/// since the voxel-map matcher takes them as its tilt prior (registration::GravityPrior).
using registration::VerticalConstraint;

struct VerticalStructureParams {
  double voxel_m = 1.0;             ///< cell edge in the lidar's x and y for the local shape analysis [m]
  double voxel_height_m = 2.0;      ///< cell height (tall cells make trunks and poles lines) [m]
  int min_points = 6;               ///< points a voxel needs [-]
  double max_tilt_rad = 15.0 * M_PI / 180.0;       ///< normals within this of horizontal, axes of vertical [rad]; ini _deg
  double planarity = 0.05;          ///< plane: smallest / middle eigenvalue below this [-]
  double min_plane_extent_m = 0.15; ///< plane: std along its second axis at least this (not a ring) [m]
  double min_thickness_m = 0.02;    ///< floor of a structure's spread across itself (range noise) [m]
  double face_margin_m = 0.15;      ///< planes this close to a voxel face they parallel are dropped [m]
  double linearity = 0.05;          ///< line: middle / largest eigenvalue below this [-]
  double min_line_extent_m = 0.2;   ///< line: std along its axis at least this [m]
  /// How far from vertical real structures stand (std) [rad]; ini vertical_lean_deg. A structure's
  /// tilt variance is its fit's plus this, so no wall or trunk counts for more than 1 / lean^2 however
  /// many points it has: facades and poles lean by tenths of a degree, trees by more, while a 64-beam
  /// sensor fits a wall's normal to hundredths.
  double lean_rad = 0.5 * M_PI / 180.0;
};

/// Constraints from the non-ground points of one sweep (\p is_ground empty or one flag per point),
/// gated around \p up_guess_lidar (unit up direction in the lidar frame, from the predicted pose).
std::vector<VerticalConstraint> findVerticalStructures(const std::vector<Eigen::Vector3d>& points_lidar,
                                                       const std::vector<uint8_t>& is_ground,
                                                       const Eigen::Vector3d& up_guess_lidar,
                                                       const VerticalStructureParams& params);

/// sum_i w_i k_i (R n_i)(R n_i)^T: the constraints rotated by \p R (e.g. into the map frame), with
/// k_i the Geman-McClure weight of the residual (R n_i) . \p up_guess at scale \p kernel_rad
/// (k_i = 1 when kernel_rad <= 0), so leaning trunks and car sides do not bias the estimate.
Eigen::Matrix3d verticalScatter(const std::vector<VerticalConstraint>& constraints, const Eigen::Matrix3d& R,
                                const Eigen::Vector3d& up_guess = Eigen::Vector3d::UnitZ(), double kernel_rad = 0);

/// Least-squares up direction of a scatter (its smallest eigenvector), sign chosen along \p hint;
/// \p info_out gets the two larger eigenvalues minus the smallest (tilt information about the two
/// horizontal axes: a single wall orientation leaves one of them at zero) [-].
Eigen::Vector3d upFromScatter(const Eigen::Matrix3d& scatter, const Eigen::Vector3d& hint,
                              Eigen::Vector2d* info_out = nullptr);

}  // namespace roadslam::odometry

#pragma once
/// \file trajectory_io.h
/// Trajectory files: TUM ("t x y z qx qy qz qw", one pose per line, '#' comments) and KITTI
/// (12 numbers per line: row-major 3x4 [R|t] of T_world_frame, with stamps in a separate times file).
/// Poses are Eigen::Isometry3d T_world_frame (translation in metres). Malformed lines throw
/// std::runtime_error naming file:line.

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace roadslam::datasets {

using PoseList = std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>>;

/// Poses with their stamps; stamps_s is empty or has one entry per pose.
struct Trajectory {
  std::vector<double> stamps_s;  ///< time of each pose [s]
  PoseList poses;                ///< T_world_frame of each pose
};

Trajectory readTum(const std::string& path);
/// Writes atomically in fixed point with 9 decimals for stamps and values (epoch stamps keep their
/// nanoseconds as far as a double holds them).
void writeTum(const std::string& path, const Trajectory& traj);

PoseList readKittiPoses(const std::string& path);
void writeKittiPoses(const std::string& path, const PoseList& poses);

/// One stamp [s] per line (KITTI times.txt).
std::vector<double> readTimes(const std::string& path);
/// Writes atomically, fixed point with 9 decimals ("%.9f"): epoch stamps keep their microseconds.
void writeTimes(const std::string& path, const std::vector<double>& stamps_s);

/// KITTI pose file + times file into one Trajectory; throws when the counts differ.
Trajectory readKittiTrajectory(const std::string& poses_path, const std::string& times_path);

/// KITTI odometry calib.txt: projection matrices P0..P3 and Tr (velodyne -> left camera).
struct KittiOdometryCalib {
  Eigen::Matrix<double, 3, 4> P[4];   ///< camera projection matrices [pixels]
  Eigen::Isometry3d T_cam0_velo;      ///< "Tr": maps velodyne-frame points into the cam0 frame [m]
};
KittiOdometryCalib readKittiOdometryCalib(const std::string& path);

/// KITTI raw calib_imu_to_velo.txt ("R: 9 numbers", "T: 3 numbers"): X_velo = R X_imu + T.
Eigen::Isometry3d readKittiRawCalibImuToVelo(const std::string& path);

/// KITTI odometry ground truth (poses of the left camera in camera frame 0) to velodyne poses in
/// velodyne frame 0: T_velo0_velo_i = Tr^-1 * T_cam0_cam_i * Tr (KITTI devkit, MANIFEST of
/// odometry-00-first16), with Tr = T_cam0_velo.
PoseList cameraPosesToVelodyne(const PoseList& T_cam0_cami, const Eigen::Isometry3d& T_cam0_velo);

/// Sum of the translation steps between consecutive poses [m].
double pathLength(const PoseList& poses);

}  // namespace roadslam::datasets

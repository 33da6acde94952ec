#include "roadslam/datasets/trajectory_io.h"

#include "line_parsing.h"
#include "roadslam/common/atomic_file.h"

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace roadslam::datasets {
namespace {

Eigen::Isometry3d fromRowMajor3x4(const std::vector<double>& v) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = v[static_cast<size_t>(4 * r + c)];
  return Eigen::Isometry3d(m);
}

std::string fmtNumber(double v) {
  std::ostringstream ss;
  ss << std::setprecision(10) << std::scientific << v;
  return ss.str();
}

}  // namespace

Trajectory readTum(const std::string& path) {
  Trajectory traj;
  detail::forEachNumberLine(path, [&](const std::vector<double>& v, int line_no) {
    detail::expectCount(v, 8, path, line_no);
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // TUM order: qx qy qz qw
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      throw std::runtime_error(path + ":" + std::to_string(line_no) +
                               ": quaternion is not unit length");
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    traj.stamps_s.push_back(v[0]);
    traj.poses.push_back(T);
  });
  return traj;
}

void writeTum(const std::string& path, const Trajectory& traj) {
  if (traj.stamps_s.size() != traj.poses.size()) {
    throw std::runtime_error("writeTum('" + path + "'): stamps and poses differ in count");
  }
  std::ostringstream out;
  out << "# t x y z qx qy qz qw\n" << std::setprecision(9) << std::fixed;
  for (size_t i = 0; i < traj.poses.size(); ++i) {
    const Eigen::Vector3d t = traj.poses[i].translation();
    const Eigen::Quaterniond q(traj.poses[i].rotation());
    out << traj.stamps_s[i] << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' '
        << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
  }
  writeFileAtomically(path, out.str());
}

PoseList readKittiPoses(const std::string& path) {
  PoseList poses;
  detail::forEachNumberLine(path, [&](const std::vector<double>& v, int line_no) {
    detail::expectCount(v, 12, path, line_no);
    poses.push_back(fromRowMajor3x4(v));
  });
  return poses;
}

void writeKittiPoses(const std::string& path, const PoseList& poses) {
  std::string out;
  for (const auto& T : poses) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) {
        out += fmtNumber(T.matrix()(r, c));
        out += (r == 2 && c == 3) ? '\n' : ' ';
      }
  }
  writeFileAtomically(path, out);
}

std::vector<double> readTimes(const std::string& path) {
  std::vector<double> t;
  detail::forEachNumberLine(path, [&](const std::vector<double>& v, int line_no) {
    detail::expectCount(v, 1, path, line_no);
    t.push_back(v[0]);
  });
  return t;
}

void writeTimes(const std::string& path, const std::vector<double>& stamps_s) {
  // Fixed point with 9 decimals: an epoch stamp (~1.7e9 s) keeps its microseconds and more; a
  // significant-digit format would cut it to 0.1 s.
  std::string out;
  char buf[64];
  for (double t : stamps_s) {
    std::snprintf(buf, sizeof buf, "%.9f\n", t);
    out += buf;
  }
  writeFileAtomically(path, out);
}

Trajectory readKittiTrajectory(const std::string& poses_path, const std::string& times_path) {
  Trajectory traj;
  traj.poses = readKittiPoses(poses_path);
  traj.stamps_s = readTimes(times_path);
  if (traj.poses.size() != traj.stamps_s.size()) {
    throw std::runtime_error("'" + poses_path + "' has " + std::to_string(traj.poses.size()) +
                             " poses but '" + times_path + "' has " +
                             std::to_string(traj.stamps_s.size()) + " stamps");
  }
  return traj;
}

KittiOdometryCalib readKittiOdometryCalib(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  KittiOdometryCalib calib;
  bool seen[5] = {false, false, false, false, false};
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = line.substr(0, colon);
    const auto v = detail::parseNumbers(line.substr(colon + 1), path, line_no);
    int idx = -1;
    if (key == "Tr") idx = 4;
    else if (key.size() == 2 && key[0] == 'P' && key[1] >= '0' && key[1] <= '3') idx = key[1] - '0';
    if (idx < 0) continue;
    detail::expectCount(v, 12, path, line_no);
    if (idx == 4) calib.T_cam0_velo = fromRowMajor3x4(v);
    else calib.P[idx] = fromRowMajor3x4(v).matrix().topRows<3>();
    seen[idx] = true;
  }
  if (!seen[4]) throw std::runtime_error(path + ": no 'Tr:' line");
  return calib;
}

Eigen::Isometry3d readKittiRawCalibImuToVelo(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  bool has_r = false, has_t = false;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    if (line.rfind("R:", 0) == 0) {
      const auto v = detail::parseNumbers(line.substr(2), path, line_no);
      detail::expectCount(v, 9, path, line_no);
      T.linear() = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(v.data());
      has_r = true;
    } else if (line.rfind("T:", 0) == 0) {
      const auto v = detail::parseNumbers(line.substr(2), path, line_no);
      detail::expectCount(v, 3, path, line_no);
      T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
      has_t = true;
    }
  }
  if (!has_r || !has_t) throw std::runtime_error(path + ": needs both 'R:' and 'T:' lines");
  return T;
}

PoseList cameraPosesToVelodyne(const PoseList& T_cam0_cami, const Eigen::Isometry3d& T_cam0_velo) {
  PoseList out;
  out.reserve(T_cam0_cami.size());
  const Eigen::Isometry3d Tr_inv = T_cam0_velo.inverse();
  for (const auto& P : T_cam0_cami) out.push_back(Tr_inv * P * T_cam0_velo);
  return out;
}

double pathLength(const PoseList& poses) {
  double len = 0;
  for (size_t i = 1; i < poses.size(); ++i)
    len += (poses[i].translation() - poses[i - 1].translation()).norm();
  return len;
}

}  // namespace roadslam::datasets

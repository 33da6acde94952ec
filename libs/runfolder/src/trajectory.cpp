#include "roadslam/runfolder/trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/pose_interpolation.h"

namespace roadslam::runfolder {

StampedTrajectory::StampedTrajectory(datasets::Trajectory t, const std::string& what) : t_(std::move(t)) {
  if (t_.stamps_s.size() != t_.poses.size())
    throw std::invalid_argument(what + ": " + std::to_string(t_.poses.size()) + " poses but " +
                                std::to_string(t_.stamps_s.size()) + " stamps");
  sorted_i_.resize(t_.stamps_s.size());
  for (size_t i = 0; i < sorted_i_.size(); ++i) sorted_i_[i] = i;
  std::stable_sort(sorted_i_.begin(), sorted_i_.end(), [&](size_t a, size_t b) { return t_.stamps_s[a] < t_.stamps_s[b]; });
  for (size_t i : sorted_i_) sorted_s_.push_back(t_.stamps_s[i]);
}

std::optional<Eigen::Isometry3d> StampedTrajectory::at(double t, double max_gap_s) const {
  const auto& st = sorted_s_;
  if (st.empty() || !(t >= st.front() && t <= st.back())) return std::nullopt;
  const size_t k = static_cast<size_t>(std::upper_bound(st.begin(), st.end(), t) - st.begin());
  if (k == st.size()) return t_.poses[sorted_i_.back()];  // t is the last stamp
  const Eigen::Isometry3d& a = t_.poses[sorted_i_[k - 1]];   // k > 0: st.front() <= t
  if (t == st[k - 1]) return a;
  const double dt = st[k] - st[k - 1];
  if (dt > max_gap_s) return std::nullopt;
  return interpolate(a, t_.poses[sorted_i_[k]], (t - st[k - 1]) / dt);
}

std::optional<size_t> StampedTrajectory::nearest(double t, double tolerance_s) const {
  const auto& st = sorted_s_;
  if (st.empty()) return std::nullopt;
  const size_t k = static_cast<size_t>(std::lower_bound(st.begin(), st.end(), t) - st.begin());
  size_t best = k < st.size() ? k : st.size() - 1;
  if (k > 0 && (k == st.size() || t - st[k - 1] <= st[k] - t)) best = k - 1;
  if (!(std::abs(st[best] - t) <= tolerance_s)) return std::nullopt;
  return sorted_i_[best];
}

StampedTrajectory readTrajectory(const std::string& path) { return StampedTrajectory(datasets::readTum(path), path); }

void writeTrajectory(const std::string& path, const StampedTrajectory& t) { datasets::writeTum(path, t.data()); }

}  // namespace roadslam::runfolder

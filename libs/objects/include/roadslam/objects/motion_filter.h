#pragma once
/// \file motion_filter.h
/// A track's motion filter: the Kalman filter on its box centre in the map frame, one class per motion
/// model (TrackerParams::motion_model: constant velocity, CTRV, an IMM of constant velocity and
/// coordinated turn). Each keeps its own state; every step writes the track's constant-velocity view
/// [x, y, vx, vy] and its covariance (Track::x, Track::P: what association, labels and outputs read).

#include <Eigen/Core>
#include <memory>

#include "roadslam/objects/params.h"

namespace roadslam::objects {

class MotionFilter {
 public:
  virtual ~MotionFilter() = default;
  virtual std::unique_ptr<MotionFilter> clone() const = 0;

  /// A new track: \p x, \p P hold the constant-velocity start (the centre, zero velocity, and their
  /// variances); \p heading_rad is the direction the object likely moves along (its box's axis, or a
  /// car face's line of sight), map frame. The filter starts from them and writes its view back.
  virtual void start(double heading_rad, Eigen::Vector4d& x, Eigen::Matrix4d& P) = 0;
  /// Prediction over \p dt >= 0 [s]; \p moving: the track is labelled moving.
  virtual void predict(double dt, bool moving, Eigen::Vector4d& x, Eigen::Matrix4d& P) = 0;
  /// Update with the box centre \p z [m] (covariance \p R [m^2]) seen \p dt [s] after the state's time:
  /// the detection is where the object was when the beam swept it, h(x) = position + dt * velocity.
  virtual void correct(const Eigen::Vector2d& z, double dt, const Eigen::Matrix2d& R, Eigen::Vector4d& x,
                       Eigen::Matrix4d& P) = 0;
  /// Update with a heading measurement \p z of the velocity [rad], sigma \p sigma [rad]; filters that do
  /// not model the heading's measurement ignore it.
  virtual void correctHeading(double /*z*/, double /*sigma*/, Eigen::Vector4d& /*x*/, Eigen::Matrix4d& /*P*/) {}
  /// The track jumped (it continued a lost one): a turn-rate estimate from before is none. Filters
  /// whose turn rate is no separate model keep their state.
  virtual void restartTurn(Eigen::Vector4d& /*x*/, Eigen::Matrix4d& /*P*/) {}
};

/// The filter of TrackerParams::motion_model, with its parameters.
std::unique_ptr<MotionFilter> makeMotionFilter(const TrackerParams& p);

/// A track's filter with value semantics: a copy of a track (the stage's snapshots, an ended track)
/// holds a copy of its filter.
class TrackFilter {
 public:
  TrackFilter() = default;
  explicit TrackFilter(std::unique_ptr<MotionFilter> f) : f_(std::move(f)) {}
  TrackFilter(const TrackFilter& o) : f_(o.f_ ? o.f_->clone() : nullptr) {}
  TrackFilter& operator=(const TrackFilter& o) {
    if (this != &o) f_ = o.f_ ? o.f_->clone() : nullptr;
    return *this;
  }
  TrackFilter(TrackFilter&&) noexcept = default;
  TrackFilter& operator=(TrackFilter&&) noexcept = default;

  MotionFilter* operator->() const { return f_.get(); }
  MotionFilter& operator*() const { return *f_; }
  const MotionFilter* get() const { return f_.get(); }
  explicit operator bool() const { return f_ != nullptr; }

 private:
  std::unique_ptr<MotionFilter> f_;
};

}  // namespace roadslam::objects

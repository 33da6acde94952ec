#pragma once
// The interacting multiple model filter of a track (TrackerParams::motion_model = imm): a constant
// velocity and a coordinated turn model on one state [x, y, vx, vy, omega] (map frame; m, m/s, rad/s).
// Blom and Bar-Shalom, "The Interacting Multiple Model Algorithm for Systems with Markovian Switching
// Coefficients", IEEE TAC 33(8), 1988; the steps below follow Bar-Shalom, Li and Kirubarajan,
// "Estimation with Applications to Tracking and Navigation", Wiley 2001, Sec. 11.6.6 (IMM: interaction,
// model-matched filtering, model probability update, combination) and Sec. 11.7 (coordinated turn with
// the turn rate in the state, as an EKF).

#include <Eigen/Core>

#include "roadslam/objects/params.h"
#include "roadslam/objects/tracker.h"

namespace roadslam::objects::imm {

/// The coordinated turn transition of \p s = [x, y, vx, vy, omega] over \p T [s]; \p F: its Jacobian.
Eigen::Matrix<double, 5, 1> ctMove(const Eigen::Matrix<double, 5, 1>& s, double T, Eigen::Matrix<double, 5, 5>* F);

/// Both models start from the track's 4-D state (Track::x, Track::P) with omega = 0 and the
/// CT model's turn rate uncertainty; model probabilities ImmParams::init_ct_probability.
void init(Track& tr, const TrackerParams& p);
/// Mixing (interaction) and each model's prediction over \p dt; Track::x, P: the combined estimate.
void predict(Track& tr, double dt, const TrackerParams& p);
/// Each model's Kalman update with the box centre \p z seen \p dt_meas after the state's time
/// (h = position + dt_meas * velocity), the model probabilities from their likelihoods, the combination.
/// Each model's EKF update with the heading \p z of the velocity (a box's axis) [rad], sigma \p sigma [rad].
void correctHeading(Track& tr, double z, double sigma, const TrackerParams& p);
/// The turn rate of both models back to a new track's (0, ImmParams::init_turn_rate_sigma_radps, no
/// correlation) and the model probabilities to ImmParams::init_ct_probability.
void restartTurn(Track& tr, const TrackerParams& p);
/// \p R: the centre's covariance [m^2].
void correct(Track& tr, const Eigen::Vector2d& z, double dt_meas, const TrackerParams& p, const Eigen::Matrix2d& R);

}  // namespace roadslam::objects::imm

#pragma once
/// \file side_input.h
/// The one check of a side input (a CAN log, a trajectory, ground truth) against the recording it
/// is given with: a file from another drive, or on another clock, is refused before the run instead
/// of leaving every sweep without a prior or a pose and a summary that says nothing.

#include <string>

namespace roadslam {

/// How far the recording may start outside a side input's span and still be its drive [s]: the
/// grabber starts its sources within seconds of each other.
constexpr double kSideInputSlack_s = 10.0;

/// Empty when \p recording_start_s (the recording's first sweep) lies within [\p first_s, \p last_s]
/// widened by \p slack_s; else "WHAT covers A to B (N s), but the recording starts at T, D s
/// before/after it: another drive, or another clock".
std::string sideInputMismatch(const std::string& what, double first_s, double last_s, double recording_start_s,
                              double slack_s = kSideInputSlack_s);

}  // namespace roadslam

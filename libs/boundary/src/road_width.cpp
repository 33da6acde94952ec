// The road's width as a check on the two sides: a side whose fit leaves the width is refitted near
// the other side moved by it (hidden curb, a line beyond the sidewalk in view), and the width itself.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "internal.h"
#include "roadslam/boundary/detector.h"

namespace roadslam::boundary {
namespace detail {

double yAt(const std::vector<Vec2>& line, double x) {
  for (size_t i = 1; i < line.size(); ++i) {
    const Vec2 &a = line[i - 1], &b = line[i];
    if (x >= a.x && x <= b.x) return b.x > a.x ? a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x) : a.y;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double deviationInBand(const std::vector<Vec2>& line, const std::vector<Vec2>& held, const Params& p, int* n) {
  double dev = 0;
  *n = 0;
  for (const auto& h : held) {
    if (h.x < p.band_min_x_m || h.x > p.band_max_x_m) continue;
    const double y = yAt(line, h.x);
    if (std::isfinite(y)) dev += std::abs(y - h.y), ++*n;
  }
  return *n > 0 ? dev / *n : 0.0;
}

}  // namespace detail
namespace {

/// Curb to curb at x (vertical gap times the mean heading's cosine) of two side fits [m].
double widthAt(const SideBoundary& l, const SideBoundary& r, double x) {
  const double m = 0.5 * (detail::polySlope(l.coeffs, x) + detail::polySlope(r.coeffs, x));
  return (detail::polyEval(l.coeffs, x) - detail::polyEval(r.coeffs, x)) / std::sqrt(1 + m * m);
}

/// The widest curb to curb where both lines are reported: a line running away diagonally (a
/// slope's edge) can start at the right offset [m].
double widestWidth(const SideBoundary& l, const SideBoundary& r, double step) {
  const double x0 = std::max(l.polyline_vehicle.front().x, r.polyline_vehicle.front().x);
  const double x1 = std::min(l.polyline_vehicle.back().x, r.polyline_vehicle.back().x);
  double w = widthAt(l, r, x0);
  for (double x = x0 + step; x <= x1 + 1e-9; x += step) w = std::max(w, widthAt(l, r, x));
  return w;
}

}  // namespace

void BoundaryDetector::checkWidth(SideBoundary& l, SideBoundary& r, const std::vector<Vec2>& pts, std::mt19937& rng,
                                  const Eigen::Isometry3d& T_map_lidar, const detail::BendFrame& arc) const {
  // A curb 1 m either side of the other side's line moved by the road's width is this side's curb:
  // wider than a parking lane's step is not (2.2 m, within width_jump_m).
  constexpr double kWidthGate = 1.0;  // [m]
  // Only wider: the road ends at the first curb, so a pair narrower than the width is taken as it is
  // (updateWidth adopts it), which also undoes a width taken from a line beyond the curb.
  const double w = widestWidth(l, r, p_.bin_m);
  if (!(w - road_width_m_ > p_.width_jump_m)) return;
  // The side that left its last accepted line (held or not) jumped; without one to tell, the side
  // whose expected line (the other side moved by the width) has curb cells near it.
  std::vector<Vec2> near[2];
  int bins[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    const int side = k == 0 ? +1 : -1;
    const auto& o = (k == 0 ? r : l).coeffs;
    std::set<int> b;
    for (const auto& q : pts) {
      const double m = detail::polySlope(o, q.x);
      if (side * q.y < p_.min_lateral_m ||
          std::abs(q.y - detail::polyEval(o, q.x) - side * road_width_m_ * std::sqrt(1 + m * m)) > kWidthGate)
        continue;
      near[k].push_back(q);
      b.insert(static_cast<int>(std::floor(q.x / p_.bin_m)));
    }
    bins[k] = static_cast<int>(b.size());
  }
  double dev[2] = {-1, -1};
  for (int j = 0; j < 2; ++j) {
    int n = 0;
    const double d = detail::deviationInBand((j == 0 ? l : r).polyline_vehicle, heldPoints(tracks_[j], T_map_lidar, arc, true), p_, &n);
    if (n > 0) dev[j] = d;
  }
  int k = dev[0] >= dev[1] ? 0 : 1;
  if (dev[k] <= p_.track_gate_m) k = -1;
  if (k < 0 && (bins[0] >= p_.min_bins) != (bins[1] >= p_.min_bins)) k = bins[0] >= p_.min_bins ? 0 : 1;
  if (k < 0) return;
  const int side = k == 0 ? +1 : -1;
  SideBoundary& s = k == 0 ? l : r;
  // Numbers last, in parentheses: the app's summary counts reasons up to " (".
  std::ostringstream why;
  why << std::fixed;
  why.precision(1);
  why << " (fit " << w << " m from the " << (k == 0 ? "right" : "left") << " side, the road is " << road_width_m_
      << " m wide)";
  SideBoundary alt = detail::fitSide(near[k], side, p_, rng);
  const SideBoundary& o = k == 0 ? r : l;
  // The refit must keep the width too: a quadratic through the corridor's cells may curve out of it.
  if (alt.found && widestWidth(k == 0 ? alt : o, k == 0 ? o : alt, p_.bin_m) - road_width_m_ > p_.width_jump_m) {
    alt.coeffs.clear();
    alt.reason = "its refit near the road's width leaves the width too";
  }
  if (alt.coeffs.empty()) {
    s.found = false;
    s.coeffs.clear();
    s.polyline_vehicle.clear();
    s.reason = "off the road's width: " + alt.reason + why.str();
    return;
  }
  if (!alt.found) alt.reason = "off the road's width: " + alt.reason + why.str();
  s = std::move(alt);
}

void BoundaryDetector::updateWidth(double w, bool known, size_t frame) {
  if (!std::isfinite(w)) return;
  // A width wider than the known one by more than width_jump_m is taken only once it persists
  // (kNewWidthFrames sweeps within kNewWidthTol): one pair of wrong lines must not move it. A much
  // narrower one at once: the first curb from the vehicle is the road's end.
  constexpr int kNewWidthFrames = 20;
  constexpr double kNewWidthTol = 0.5;  // [m]
  if (known && p_.width_jump_m > 0 && road_width_m_ - w > p_.width_jump_m) {
    road_width_m_ = w;
  } else if (known && p_.width_jump_m > 0 && w - road_width_m_ > p_.width_jump_m) {
    if (new_width_count_ > 0 && std::abs(w - new_width_m_) <= kNewWidthTol) {
      ++new_width_count_;
    } else {
      new_width_m_ = w, new_width_count_ = 1;
    }
    if (new_width_count_ < kNewWidthFrames) return;
    road_width_m_ = new_width_m_;
  } else {
    road_width_m_ = known ? 0.8 * road_width_m_ + 0.2 * w : w;
  }
  new_width_count_ = 0;
  road_width_frame_ = frame;
}

}  // namespace roadslam::boundary

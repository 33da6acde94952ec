// Left/right boundary fits in the vehicle frame.
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>

#include "internal.h"

namespace roadslam::boundary::detail {
namespace {

const char* sideName(int side) { return side > 0 ? "left" : "right"; }

/// Least squares y = sum c_i x^i over \p pts.
std::vector<double> lsq(const std::vector<Vec2>& pts, int degree) {
  Eigen::MatrixXd A(pts.size(), degree + 1);
  Eigen::VectorXd b(pts.size());
  for (size_t r = 0; r < pts.size(); ++r) {
    double xp = 1;
    for (int c = 0; c <= degree; ++c, xp *= pts[r].x) A(r, c) = xp;
    b(r) = pts[r].y;
  }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  return std::vector<double>(c.data(), c.data() + c.size());
}

/// Roads bend gently and a side stays on its side: reject hypotheses that curl or cross the
/// vehicle's path within the band.
bool plausible(const std::vector<double>& c, int side, const Params& p) {
  if (std::abs(c[1]) > p.max_heading || (c.size() > 2 && std::abs(c[2]) > p.max_curvature)) return false;
  for (double x = p.band_min_x_m; x <= p.band_max_x_m; x += 0.25 * (p.band_max_x_m - p.band_min_x_m))
    if (side * polyEval(c, x) < p.min_lateral_m) return false;
  return true;
}

struct Score {
  int bins = 0, inliers = 0;
  double abs_c0 = 1e9;
  bool better(const Score& o) const {
    if (bins != o.bins) return bins > o.bins;
    if (inliers != o.inliers) return inliers > o.inliers;
    return abs_c0 < o.abs_c0;
  }
};

Score score(const std::vector<Vec2>& pts, const std::vector<double>& c, const Params& p,
            std::vector<Vec2>* inl = nullptr) {
  std::set<int> bins;
  Score s;
  for (const auto& q : pts) {
    if (std::abs(q.y - polyEval(c, q.x)) > p.ransac_inlier_m) continue;
    ++s.inliers;
    bins.insert(static_cast<int>(std::floor(q.x / p.bin_m)));
    if (inl) inl->push_back(q);
  }
  s.bins = static_cast<int>(bins.size());
  s.abs_c0 = std::abs(c.front());
  return s;
}

/// The best of ransac_iterations minimal-sample hypotheses (Fischler & Bolles 1981) by Score; empty
/// when none is plausible.
std::vector<double> bestHypothesis(const std::vector<Vec2>& pts, int side, int degree, const Params& p,
                                   std::mt19937& rng, Score& best) {
  const size_t m = static_cast<size_t>(degree) + 1;
  std::uniform_int_distribution<size_t> pick(0, pts.size() - 1);
  std::vector<double> best_c;
  for (int it = 0; it < p.ransac_iterations; ++it) {
    std::vector<Vec2> sample;
    for (size_t k = 0; k < m; ++k) sample.push_back(pts[pick(rng)]);
    bool spread = true;  // distinct x so the minimal system is well conditioned
    for (size_t a = 0; a < m; ++a)
      for (size_t b = a + 1; b < m; ++b) spread = spread && std::abs(sample[a].x - sample[b].x) > p.bin_m;
    if (!spread) continue;
    auto c = lsq(sample, degree);
    if (!plausible(c, side, p)) continue;
    const Score s = score(pts, c, p);
    if (best_c.empty() || s.better(best)) best = s, best_c = c;
  }
  return best_c;
}

/// The road ends at the first curb from the vehicle: a line of cells at least kInnerGap nearer the
/// vehicle, nearly parallel, covering inner_curb_share of the best line's bins is the curb and the
/// best line a sidewalk's far edge (over many sweeps that edge can gather more bins: hills.ini).
void preferInnerLine(const std::vector<Vec2>& pts, int side, int degree, int min_bins, const Params& p,
                     Score& best, std::vector<double>& best_c) {
  constexpr double kInnerGap = 2.5;      // [m] a sidewalk (3 m) in, not a parked car's sill (within 2.2 m of the curb)
  constexpr double kMaxHeadingDiff = 0.1;  // |c1 - c1'| of "parallel" [-]
  if (p.inner_curb_share <= 0 || p.method == Method::Thesis) return;
  std::vector<Vec2> inner;
  for (const auto& q : pts)
    if (side * (q.y - polyEval(best_c, q.x)) < -kInnerGap) inner.push_back(q);
  if (inner.size() < std::max<size_t>(static_cast<size_t>(degree) + 1, static_cast<size_t>(min_bins))) return;
  Score si;
  std::mt19937 rng(static_cast<unsigned>(p.ransac_seed) + 1);  // its own draws: the other fits stay as they were
  const auto ci = bestHypothesis(inner, side, degree, p, rng, si);
  if (ci.empty() || si.bins < min_bins || si.bins < p.inner_curb_share * best.bins ||
      std::abs(ci[1] - best_c[1]) > kMaxHeadingDiff)
    return;
  best = score(pts, ci, p), best_c = ci;
}

/// The polyline over the band along the stretch of evidence spanning most of it: gaps between inliers up
/// to max_bridge_m are bridged (curb seen on both sides of a parked car), no farther than
/// max_extrapolation_m beyond the last inlier. Bridged length lowers the confidence (half weight).
void spanPolyline(std::vector<Vec2> inl, const std::vector<double>& c, const Params& p, SideBoundary& out) {
  std::sort(inl.begin(), inl.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x; });
  // Stretches of inliers separated by more than max_bridge_m; report the one spanning most of the band.
  // The thesis baseline's points are one corner per shape, metres apart: its line is not cut.
  const double bridge = p.method == Method::Thesis ? std::numeric_limits<double>::infinity() : p.max_bridge_m;
  double x0 = 0, x1 = -1;
  for (size_t b = 0, i = 1; i <= inl.size(); ++i) {
    if (i < inl.size() && inl[i].x - inl[i - 1].x <= bridge) continue;
    const double a0 = std::max(p.band_min_x_m, inl[b].x - p.max_extrapolation_m);
    const double a1 = std::min(p.band_max_x_m, inl[i - 1].x + p.max_extrapolation_m);
    if (a1 - a0 > x1 - x0) x0 = a0, x1 = a1;
    b = i;
  }
  int bridged = 0, total = 0;
  for (double x = x0; x <= x1 + 1e-9; x += p.polyline_step_m) {
    out.polyline_vehicle.push_back({x, polyEval(c, x)});
    const auto it = std::lower_bound(inl.begin(), inl.end(), x - p.bin_m, [](const Vec2& q, double v) { return q.x < v; });
    const bool supported = it != inl.end() && it->x <= x + p.bin_m;
    bridged += !supported, ++total;
  }
  out.bridged_m = bridged * p.polyline_step_m;
  if (total > 0) out.confidence *= 1.0 - 0.5 * bridged / total;
}

/// RANSAC (Fischler & Bolles 1981) over minimal samples, scored by covered distance bins so a long
/// thin curb wins over a dense short blob; refined by least squares on the inliers.
SideBoundary ransac(const std::vector<Vec2>& pts, int side, int degree, int min_bins, const Params& p,
                    std::mt19937& rng) {
  SideBoundary out;
  out.candidates = static_cast<int>(pts.size());
  const size_t m = static_cast<size_t>(degree) + 1;
  std::ostringstream why;
  if (pts.size() < std::max<size_t>(m, static_cast<size_t>(min_bins))) {
    why << "too few " << (p.method == Method::Thesis ? "shapes" : "curb points") << " on the " << sideName(side)
        << " (" << pts.size() << ")";
    out.reason = why.str();
    return out;
  }
  Score best;
  std::vector<double> best_c = bestHypothesis(pts, side, degree, p, rng, best);
  if (best_c.empty() || best.bins < min_bins) {
    why << "no consistent " << sideName(side) << " boundary: best fit covers " << best.bins << " of "
        << min_bins << " needed " << p.bin_m << " m bins";
    out.reason = why.str();
    return out;
  }
  preferInnerLine(pts, side, degree, min_bins, p, best, best_c);
  std::vector<Vec2> inl;
  for (int r = 0; r < 2; ++r) {
    inl.clear();
    score(pts, best_c, p, &inl);
    if (inl.size() < m) break;
    const auto c = lsq(inl, degree);
    if (plausible(c, side, p)) best_c = c;
  }
  out.found = true;
  out.reason = "ok";
  out.coeffs = best_c;
  out.inliers = static_cast<int>(inl.size());
  std::set<int> band_bins;
  for (const auto& q : inl) {
    if (q.x >= p.band_min_x_m && q.x <= p.band_max_x_m) band_bins.insert(static_cast<int>(std::floor(q.x / p.bin_m)));
  }
  if (static_cast<int>(band_bins.size()) < p.min_band_bins) {
    // Support only behind or beside the vehicle: a polynomial would be a guess in the band.
    out.found = false;
    why << "the " << sideName(side) << " curb is not seen ahead (" << band_bins.size() << " of " << p.min_band_bins
        << " bins in the band; hidden by obstacles?)";
    out.reason = why.str();
    out.polyline_vehicle.clear();
    return out;
  }
  const double band_bins_total = std::ceil((p.band_max_x_m - p.band_min_x_m) / p.bin_m);
  out.confidence = std::min(1.0, band_bins.size() / band_bins_total) * out.inliers / std::max(1, out.candidates);
  spanPolyline(inl, best_c, p, out);
  if (out.polyline_vehicle.size() < 2) {
    out.found = false;
    out.reason = std::string("the ") + sideName(side) + " boundary lies outside the reported band";
  }
  return out;
}

}  // namespace

SideBoundary fitSide(const std::vector<Vec2>& pts, int side, const Params& p, std::mt19937& rng) {
  std::vector<Vec2> cand;
  for (const auto& q : pts) {
    const double lat = side * q.y;
    if (q.x >= p.fit_min_x_m && q.x <= p.fit_max_x_m && lat >= p.min_lateral_m && lat <= p.max_lateral_m) cand.push_back(q);
  }
  return ransac(cand, side, p.poly_degree, p.min_bins, p, rng);
}

SideBoundary fitSideThesis(const std::vector<Obstacle>& rects, int side, const Params& p, std::mt19937& rng) {
  // Thesis: each shape's rectangle stands for the shape; the corner nearest the vehicle's axis
  // marks the boundary; a straight line is fitted through these corners.
  std::vector<Vec2> cand;
  for (const auto& o : rects) {
    const double c = std::cos(o.yaw_rad), s = std::sin(o.yaw_rad);
    Vec2 best;
    bool any = false;
    for (int k = 0; k < 4; ++k) {
      const double u = (k & 1 ? 0.5 : -0.5) * o.length_m, v = (k & 2 ? 0.5 : -0.5) * o.width_m;
      const Vec2 q{o.center.x + c * u - s * v, o.center.y + s * u + c * v};
      if (side * q.y > 0 && (!any || std::abs(q.y) < std::abs(best.y))) best = q, any = true;
    }
    const double lat = side * best.y;
    if (any && best.x >= p.fit_min_x_m && best.x <= p.fit_max_x_m && lat >= p.min_lateral_m && lat <= p.max_lateral_m) cand.push_back(best);
  }
  return ransac(cand, side, 1, 2, p, rng);
}

}  // namespace roadslam::boundary::detail

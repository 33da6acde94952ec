// The frame of the side fits: the driven path's arc, or a bend ahead where the curb map bends.
#include <algorithm>
#include <array>
#include <bitset>
#include <cmath>
#include <unordered_set>

#include "internal.h"

namespace roadslam::boundary::detail {
namespace {

constexpr double kVoteDBin = 0.25;  ///< offset bin of the vote [m]; pairs of bins span a curb's 0.2 m cell
constexpr int kSBins = 64;          ///< 1 m arc-length bins voted over [-]

/// Votes of \p f: per side, the most 1 m arc-length bins (0..kSBins m) whose cells share one offset
/// (two adjacent kVoteDBin bins), summed over both sides. A curb concentric with the frame's path
/// fills one offset bin over its whole length; one the frame misses spreads over many.
int votes(const std::vector<Vec2>& cells, const BendFrame& f, const Params& p) {
  const int nd = static_cast<int>(std::ceil(p.max_lateral_m / kVoteDBin)) + 2;
  std::array<std::vector<std::bitset<kSBins>>, 2> m;
  m[0].assign(nd, {}), m[1].assign(nd, {});
  for (const auto& q : cells) {
    Vec2 a;
    if (!f.toArc(q, a) || a.x < 0 || a.x >= kSBins || std::abs(a.y) < p.min_lateral_m || std::abs(a.y) > p.max_lateral_m) continue;
    m[a.y > 0 ? 0 : 1][static_cast<size_t>(std::abs(a.y) / kVoteDBin)].set(static_cast<size_t>(a.x));
  }
  int total = 0;
  for (const auto& side : m) {
    size_t best = 0;
    for (size_t i = 0; i + 1 < side.size(); ++i) best = std::max(best, (side[i] | side[i + 1]).count());
    total += static_cast<int>(best);
  }
  return total;
}

}  // namespace

BendFrame chooseFrame(const std::vector<Vec2>& cells, double kappa_path, const Params& p, int out_votes[2]) {
  BendFrame path;
  path.a.kappa = kappa_path;
  if (p.bend_max_curvature <= 0 || p.bend_curvature_steps < 1 || p.bend_step_m <= 0) {
    if (out_votes) out_votes[0] = out_votes[1] = 0;
    return path;
  }
  // Cells ahead and beside, thinned to one per 0.5 m: the vote counts bins, not points.
  std::vector<Vec2> ahead;
  std::unordered_set<int64_t> taken;
  const double r2 = p.fit_max_x_m * p.fit_max_x_m;
  for (const auto& q : cells)
    if (q.x > -1.0 && q.x * q.x + q.y * q.y <= r2 && taken.insert(cellKey(q.x, q.y, 0.5)).second) ahead.push_back(q);
  const int base = votes(ahead, path, p);
  BendFrame best = path;
  int best_votes = base + p.bend_margin_bins - 1;  // a bend must beat the path by the margin
  for (double sb = 0; sb < p.band_max_x_m; sb += p.bend_step_m) {
    for (int k = -p.bend_curvature_steps; k <= p.bend_curvature_steps; ++k) {
      BendFrame f = path;
      f.s_bend = sb;
      f.b.kappa = p.bend_max_curvature * k / p.bend_curvature_steps;
      if (std::abs(f.b.kappa - kappa_path) < 1e-6) continue;  // the path itself
      const int v = votes(ahead, f, p);
      if (v > best_votes) best = f, best_votes = v;
    }
  }
  // Refine round the coarse winner on a grid 3x finer (the coarse grid is ~1 m off a real bend).
  const BendFrame coarse = best;
  const double dk = p.bend_max_curvature / p.bend_curvature_steps / 3, ds = p.bend_step_m / 3;
  for (int i = -3; coarse.bent() && i <= 3; ++i) {
    for (int k = -3; k <= 3; ++k) {
      BendFrame f = coarse;
      f.s_bend = std::max(0.0, coarse.s_bend + i * ds);
      f.b.kappa = coarse.b.kappa + k * dk;
      if ((i == 0 && k == 0) || std::abs(f.b.kappa) > p.bend_max_curvature) continue;
      const int v = votes(ahead, f, p);
      if (v > best_votes) best = f, best_votes = v;
    }
  }
  if (out_votes) out_votes[0] = best.bent() ? best_votes : base, out_votes[1] = base;
  return best;
}

}  // namespace roadslam::boundary::detail

#include "roadslam/preprocess/ground_segmentation.h"
#include "roadslam/preprocess/ransac_ground.h"

#include "param_utils.h"
#include "roadslam/common/param_table.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace roadslam::preprocess {
namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

/// atan2 by a minimax polynomial on [0, 1] (max error ~1e-5 rad, far below a sector's width);
/// libm's atan2f was a third of the labelling time.
inline float fastAtan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float mx = std::max(ax, ay);
  if (mx == 0.f) return 0.f;
  const float a = std::min(ax, ay) / mx, s = a * a;
  float r = ((-0.0464964749f * s + 0.15931422f) * s - 0.327622764f) * s * a + a;
  if (ay > ax) r = 1.57079637f - r;
  if (x < 0) r = 3.14159274f - r;
  return y < 0 ? -r : r;
}

/// One (sector, range bin) cell: its prototype (lowest return) and highest return.
struct Cell {
  float min_z = kInf;  ///< z of the lowest return [m]
  float r = 0;         ///< horizontal range of the lowest return [m]
  float top_z = -kInf; ///< z of the highest return [m]
};

/// Ground line z = m r + b assigned to a cell; b = +inf when none is in reach.
struct CellLine {
  float m = 0, b = kInf;
};

struct Segment {
  double m, b, r0, r1;  // z = m r + b over [r0, r1] (horizontal range [m])
  double at(double r) const { return m * r + b; }
};

/// Incremental least squares of z = m r + b (Himmelsbach 2010, Sec. III-B).
struct LineAccumulator {
  double n = 0, sr = 0, sz = 0, srr = 0, srz = 0, szz = 0, r_first = 0, r_last = 0;
  void add(double r, double z) {
    if (n == 0) r_first = r;
    r_last = r;
    n += 1, sr += r, sz += z, srr += r * r, srz += r * z, szz += z * z;
  }
  /// Slope, intercept and RMS residual; false when degenerate.
  bool fit(double& m, double& b, double& rms) const {
    const double den = n * srr - sr * sr;
    if (n < 2 || std::abs(den) < 1e-12) return false;
    m = (n * srz - sr * sz) / den;
    b = (sz - m * sr) / n;
    const double sse = szz - 2 * m * srz - 2 * b * sz + m * m * srr + 2 * m * b * sr + n * b * b;
    rms = std::sqrt(std::max(0.0, sse) / n);
    return true;
  }
};

/// Extracts the line segments of one sector from its prototypes (r, z) in increasing range
/// (Himmelsbach 2010, Sec. III-B; linefit). A prototype that breaks the current line (slope, fit
/// error, deviation) starts a new line together with the last ground prototype when the slope
/// between the two is admissible, so crests and dips are followed even between sparse rings.
class SectorFitter {
 public:
  /// \p blind_r: range [m] inside which no return can lie on a flat road under the car (the
  /// lowest beam meets the road there), see restart().
  SectorFitter(const GroundSegParams& p, double blind_r) : p_(p), blind_r_(blind_r) {}

  std::vector<Segment> run(const Cell* cells, int bins) {
    for (int i = 0; i < bins; ++i) {
      const Cell& c = cells[i];
      if (c.min_z == kInf) continue;
      // The lowest return under a vertical structure (wall, car side) only extends the ground
      // profile when it lies on it: the foot of a wall a few cm up would otherwise bend the line.
      if (c.top_z - c.min_z > p_.tall_cell_height_m && !onProfile(c.r, c.min_z)) {
        occluded_ = have_last_, stood_ = true;
        continue;
      }
      if (extend(c.r, c.min_z) || restart(c.r, c.min_z)) {
        have_last_ = true, last_r_ = c.r, last_z_ = c.min_z, occluded_ = false;
      } else {
        occluded_ = have_last_;
      }
    }
    finish();
    return std::move(segs_);
  }

 private:
  bool slopeOk(double r0, double z0, double r1, double z1) const {
    return std::abs(z1 - z0) <= p_.max_slope * std::max(r1 - r0, 1e-6);
  }

  bool onProfile(double r, double z) const {
    double m, b, rms;
    if (cur_.n >= 2 && cur_.fit(m, b, rms)) return std::abs(z - (m * r + b)) <= p_.max_dist_to_line_tall_m;
    return !segs_.empty() && std::abs(z - segs_.back().at(r)) <= p_.max_dist_to_line_tall_m;
  }

  /// Adds (r, z) to the current line if it stays a ground line; otherwise closes the line.
  bool extend(double r, double z) {
    if (cur_.n == 1 && slopeOk(cur_.r_last, cur_.sz, r, z)) {
      cur_.add(r, z);
      return true;
    }
    if (cur_.n < 2) return false;
    LineAccumulator trial = cur_;
    trial.add(r, z);
    double cm, cb, cr, tm, tb, tr;
    if (cur_.fit(cm, cb, cr) && std::abs(z - (cm * r + cb)) <= p_.max_step_m && slopeOk(last_r_, last_z_, r, z) &&
        trial.fit(tm, tb, tr) && std::abs(tm) <= p_.max_slope && tr <= p_.max_fit_error_m) {
      cur_ = trial;
      return true;
    }
    finish();
    return false;
  }

  /// Starts a new line at (r, z): bridged from the last ground prototype, or on its own.
  bool restart(double r, double z) {
    cur_ = LineAccumulator{};
    // A bridge may bend the profile by at most max_slope_change (crests, dips), which keeps it
    // from climbing the foot of a wall whose lowest return is a few bins further on.
    // parked_car_rules: over a gap where something stood (a prototype was rejected) the target may
    // be seen over it: from the road before a parked car, the next car's bonnet 7 m on is as gentle
    // a climb as a crest between two sparse rings. There it may rise no more than a line
    // starting after a gap (max_start_height_m): a curb's sidewalk still, a bonnet not.
    const bool capped = occluded_ && p_.parked_car_rules;
    const double ref_z = segs_.empty() ? last_z_ : segs_.back().at(r);
    double tol = p_.max_step_m + p_.max_slope_change * (r - last_r_);
    if (capped) tol = std::min(tol, p_.max_start_height_m);
    const bool bends_ok = (segs_.empty() && !capped) || std::abs(z - ref_z) <= tol;
    if (have_last_ && slopeOk(last_r_, last_z_, r, z) && bends_ok && r - last_r_ <= p_.max_bridge_m) {
      cur_.add(last_r_, last_z_);
      cur_.add(r, z);
      return true;
    }
    bool ok;
    if (segs_.empty()) {
      // parked_car_rules: linefit lets a first line start up to max_slope * r above the road. That
      // holds only where the road itself can be hit and seen: not inside the lowest beam's blind
      // circle (a return there needs the road to rise towards it, while a parked car's end face or
      // bonnet 0.8-1 m up passes, and a line through face and bonnet extrapolates to within
      // max_start_height_m of the road under the car), nor, optionally, behind a vertical
      // structure (a bonnet seen over the car's end). There the line must start at the road's
      // height.
      const bool level = (r < blind_r_ && p_.parked_car_rules) || (stood_ && p_.level_start_behind_structure);
      const double slack = level ? 0.0 : p_.max_slope * r;
      ok = std::abs(z + p_.sensor_height_m) <= p_.max_start_height_m + slack;
    } else {
      const Segment& last = segs_.back();
      const double tol = (r - last.r1 <= p_.max_gap_m) ? p_.max_step_m : p_.max_start_height_m;
      ok = std::abs(z - last.at(r)) <= tol;
    }
    if (ok) cur_.add(r, z);
    return ok;
  }

  /// Closes the current line. The first segment of a sector must pass under the car: its height
  /// at r = 0 within max_start_height_m of the road under the sensor (linefit's start check).
  void finish() {
    double m, b, rms;
    if (cur_.n >= 2 && cur_.fit(m, b, rms) &&
        (!segs_.empty() || std::abs(b + p_.sensor_height_m) <= p_.max_start_height_m)) {
      segs_.push_back({m, b, cur_.r_first, cur_.r_last});
    }
    cur_ = LineAccumulator{};
  }

  const GroundSegParams& p_;
  double blind_r_;
  std::vector<Segment> segs_;
  LineAccumulator cur_;
  bool have_last_ = false;  // a prototype was accepted as ground
  bool occluded_ = false;   // a prototype was rejected since the last ground prototype
  bool stood_ = false;      // a vertical structure was seen in the sector (tall cell)
  double last_r_ = 0, last_z_ = 0;
};

/// For every bin of a sector, the segment covering it (or the nearest within max_gap_m).
void assignBins(const std::vector<Segment>& segs, int bins, const GroundSegParams& p, CellLine* out) {
  std::vector<float> best(static_cast<size_t>(bins), kInf);
  for (const auto& s : segs) {
    const int i0 = std::max(0, static_cast<int>((s.r0 - p.max_gap_m) / p.bin_length_m));
    const int i1 = std::min(bins - 1, static_cast<int>((s.r1 + p.max_gap_m) / p.bin_length_m));
    for (int i = i0; i <= i1; ++i) {
      const double rc = (i + 0.5) * p.bin_length_m;
      const float dist = static_cast<float>(std::max({0.0, s.r0 - rc, rc - s.r1}));
      if (dist < best[static_cast<size_t>(i)]) {
        best[static_cast<size_t>(i)] = dist;
        out[i] = {static_cast<float>(s.m), static_cast<float>(s.b)};
      }
    }
  }
}
/// Cell index of every point (-1 beyond max range) and the prototype of every cell.
struct Grid {
  int sectors = 0, bins = 0;
  float tan_lowest = 0;  ///< tan of the lowest elevation of any return: the lowest beam's [-]
  std::vector<Cell> cells;
  std::vector<int32_t> cell_of;
};

void binPoints(const std::vector<ScanPoint>& pts, const GroundSegParams& p, Grid& g) {
  g.sectors = p.num_sectors;
  g.bins = static_cast<int>(std::ceil(p.max_range_m / p.bin_length_m));
  g.cells.assign(static_cast<size_t>(g.sectors) * static_cast<size_t>(g.bins), Cell{});
  g.cell_of.assign(pts.size(), -1);
  g.tan_lowest = 0;
  const float inv_bin = static_cast<float>(1.0 / p.bin_length_m);
  const auto max_r = static_cast<float>(p.max_range_m);
  const float sec_scale = static_cast<float>(g.sectors / (2 * M_PI));
  for (size_t i = 0; i < pts.size(); ++i) {
    const auto& q = pts[i];
    const float r = std::sqrt(q.x * q.x + q.y * q.y);
    if (!(r < max_r) || !std::isfinite(q.z)) continue;  // also NaN / inf: non-ground, no UB cast
    const int bin = std::min(g.bins - 1, static_cast<int>(r * inv_bin));
    const float az = fastAtan2(q.y, q.x) + static_cast<float>(M_PI);
    const int sec = std::min(g.sectors - 1, static_cast<int>(az * sec_scale));
    const int c = sec * g.bins + bin;
    g.cell_of[i] = c;
    Cell& cell = g.cells[static_cast<size_t>(c)];
    if (q.z < cell.min_z) cell.min_z = q.z, cell.r = r;
    cell.top_z = std::max(cell.top_z, q.z);
    if (r > 0) g.tan_lowest = std::min(g.tan_lowest, q.z / r);
  }
}

/// The line for cell \p c, or a neighbour sector's (same bin) when its own sector has none.
const CellLine* lineFor(const Grid& g, const std::vector<CellLine>& lines, size_t c) {
  if (lines[c].b != kInf) return &lines[c];
  const auto S = static_cast<size_t>(g.sectors), B = static_cast<size_t>(g.bins);
  const size_t bin = c % B, sec = c / B;
  for (size_t n : {(sec + S - 1) % S * B + bin, (sec + 1) % S * B + bin})
    if (lines[n].b != kInf) return &lines[n];
  return nullptr;
}

/// Shared body of segmentGround / segmentGroundWithHeights; \p heights may be null.
std::vector<uint8_t> label(const std::vector<ScanPoint>& pts, const GroundSegParams& p,
                           GroundSegStats& st, std::vector<float>* heights) {
  thread_local Grid g;  // scratch reused per thread: no per-sweep allocation or page faults
  thread_local std::vector<CellLine> lines;
  binPoints(pts, p, g);
  lines.assign(g.cells.size(), CellLine{});
  // The lowest beam meets a flat road under the car at h / tan(-elevation) (VLP-16: 1.9 m / tan 15
  // deg = 7.1 m); taken from the returns themselves, it holds for any sensor and crop (nearer low
  // returns, e.g. merged map points, only shrink it).
  const double blind_r = g.tan_lowest < 0 ? p.sensor_height_m / -g.tan_lowest : 0.0;
  for (int s = 0; s < g.sectors; ++s) {
    const size_t off = static_cast<size_t>(s) * static_cast<size_t>(g.bins);
    const auto segs = SectorFitter(p, blind_r).run(&g.cells[off], g.bins);
    st.segments += segs.size();
    assignBins(segs, g.bins, p, &lines[off]);
  }
  std::vector<uint8_t> labels(pts.size(), 0);
  if (heights) heights->assign(pts.size(), std::numeric_limits<float>::quiet_NaN());
  const auto tol = static_cast<float>(p.max_dist_to_line_m);
  const auto tol_tall = static_cast<float>(std::min(p.max_dist_to_line_m, p.max_dist_to_line_tall_m));
  const auto tall = static_cast<float>(p.tall_cell_height_m);
  for (size_t i = 0; i < pts.size(); ++i) {
    if (g.cell_of[i] < 0) continue;
    const auto c = static_cast<size_t>(g.cell_of[i]);
    const CellLine* line = lineFor(g, lines, c);
    if (!line) {
      ++st.unassigned;
      continue;
    }
    const auto& q = pts[i];
    const float h = q.z - (line->m * std::sqrt(q.x * q.x + q.y * q.y) + line->b);
    if (heights) (*heights)[i] = h;
    // A cell holding a vertical structure (wall, curb, car side) gets the tight tolerance, so the
    // foot of the structure is not taken for ground while the road in front of it still is.
    const float t = g.cells[c].top_z - g.cells[c].min_z > tall ? tol_tall : tol;
    labels[i] = std::abs(h) <= t;
    st.ground += labels[i];
  }
  return labels;
}
}  // namespace

std::vector<uint8_t> segmentGround(const std::vector<ScanPoint>& pts, const GroundSegParams& p,
                                   GroundSegStats* stats) {
  GroundSegStats st;
  auto labels = label(pts, p, st, nullptr);
  if (stats) *stats = st;
  return labels;
}

GroundLabels segmentGroundWithHeights(const std::vector<ScanPoint>& pts, const GroundSegParams& p) {
  GroundLabels out;
  out.ground = label(pts, p, out.stats, &out.height_above_ground_m);
  return out;
}

size_t removeGroundLinefit(std::vector<ScanPoint>& pts, const GroundSegParams& p) {
  return removeLabelled(pts, segmentGround(pts, p));
}

void GroundSegParams::fields(ParamTable& t) {
  t.num("seg_sectors", num_sectors);
  t.num("seg_bin_length_m", bin_length_m);
  t.num("seg_max_range_m", max_range_m);
  t.num("seg_sensor_height_m", sensor_height_m);
  t.num("seg_max_start_height_m", max_start_height_m);
  t.num("seg_max_slope", max_slope);
  t.num("seg_max_fit_error_m", max_fit_error_m);
  t.num("seg_max_step_m", max_step_m);
  t.num("seg_max_dist_to_line_m", max_dist_to_line_m);
  t.num("seg_max_gap_m", max_gap_m);
  t.num("seg_max_bridge_m", max_bridge_m);
  t.num("seg_max_slope_change", max_slope_change);
  t.num("seg_max_dist_to_line_tall_m", max_dist_to_line_tall_m);
  t.num("seg_tall_cell_height_m", tall_cell_height_m);
  t.flag("seg_parked_car_rules", parked_car_rules);
  t.flag("seg_level_start_behind_structure", level_start_behind_structure);
}

void GroundSegParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(num_sectors >= 1 && num_sectors <= 3600, s, "seg_sectors", "must be in [1, 3600]");
  detail::require(bin_length_m > 0 && max_range_m > bin_length_m, s, "seg_bin_length_m/seg_max_range_m",
                  "need 0 < bin length < max range");
  detail::require(max_range_m / bin_length_m <= 10000, s, "seg_bin_length_m", "too many range bins");
  detail::require(max_slope > 0 && max_fit_error_m > 0 && max_step_m > 0 && max_dist_to_line_m > 0, s,
                  "seg_max_*", "thresholds must be > 0");
}

void GroundSegParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

}  // namespace roadslam::preprocess

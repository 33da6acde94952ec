#include "roadslam/pipeline/live_gnss.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "roadslam/gnss/nmea.h"

namespace roadslam::pipeline {

gnss_fusion::GnssFactor recordedFixFactor(const gnss::GnssFix& f, double t_s, const gnss::EnuFrame& enu,
                                          const gnss_fusion::GnssFusionParams& p) {
  gnss_fusion::GnssFactor factor;
  factor.t_s = t_s;
  factor.p_enu = enu.toEnu(f.position);
  factor.cov = f.covarianceEnu(p.uere_m, p.fallback_sigma_m);
  if (!std::isfinite(f.hdop)) {
    const double s = p.fallback_sigma_m;
    factor.cov = Eigen::Vector3d(s * s, s * s, 1e6).asDiagonal();
  }
  return factor;
}

LiveGnss::LiveGnss(const gnss_fusion::GnssFusionParams& p) : online_(p), p_(p) {
  counts_.source = p.live_source_label;
  counts_.source_chosen = has_source_ = !p.live_source_label.empty();
}

void LiveGnss::post(const gnss::GnssFix& f) {
  std::lock_guard<std::mutex> lock(m_);
  if (!has_source_ && !f.valid()) {  // no source has a fix yet: kept per source until one has
    ++no_fix_before_source_[f.label];
    ++counts_.epochs;
    ++counts_.no_fix;
    return;
  }
  if (!has_source_) chooseSource(f.label);  // the first source with a fix
  if (f.label != counts_.source) {
    ++counts_.other_sources;
    return;
  }
  ++counts_.epochs;
  if (!f.valid()) {
    ++counts_.no_fix;
    return;
  }
  pending_.push_back(f);
}

// The no-fix records posted before the choice go to their own source: the one chosen, or the others.
void LiveGnss::chooseSource(const std::string& label) {
  counts_.source = label;
  has_source_ = true;
  counts_.epochs = counts_.no_fix = 0;
  for (const auto& [l, n] : no_fix_before_source_) (l == label ? counts_.no_fix : counts_.other_sources) += n;
  counts_.epochs = counts_.no_fix;
  no_fix_before_source_.clear();
}

std::optional<Eigen::Isometry3d> LiveGnss::correct(double t_s, const Eigen::Isometry3d& T_map_lidar) {
  std::lock_guard<std::mutex> lock(m_);
  std::stable_sort(pending_.begin(), pending_.end(),
                   [](const gnss::GnssFix& a, const gnss::GnssFix& b) { return a.t_receive_s < b.t_receive_s; });
  std::size_t k = 0;
  for (; k < pending_.size() && pending_[k].t_receive_s <= t_s; ++k) {
    const auto& f = pending_[k];
    if (!enu_) {
      origin_ = f.position;
      enu_.emplace(f.position);
    }
    online_.addFix(recordedFixFactor(f, f.t_receive_s, *enu_, p_));
    ++counts_.fixes;
  }
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(k));
  const auto T = online_.addNode(t_s, T_map_lidar);
  const auto& st = online_.stats();
  counts_.solves = st.solves;
  counts_.failed = st.failed;
  counts_.rejected = st.rejected;
  counts_.anchored = online_.anchored();
  return T;
}

LiveGnssCounts LiveGnss::counts() const {
  std::lock_guard<std::mutex> lock(m_);
  return counts_;
}

std::optional<gnss::Geodetic> LiveGnss::origin() const {
  std::lock_guard<std::mutex> lock(m_);
  return origin_;
}

std::string LiveGnss::statusLine() const {
  const LiveGnssCounts c = counts();
  char s[200];
  std::string source;  // "GNSS" alone while no record has a fix, or for a feed whose records carry no label
  if (c.source_chosen || !c.source.empty()) {
    source = " from " + c.source + (c.source_chosen ? " (live_source_label" : " (first seen");
    source += c.other_sources ? "; " + std::to_string(c.other_sources) + " records of other sources left out)" : ")";
  }
  std::snprintf(s, sizeof s, ": %zu fixes (%zu no fix), %zu solves (%zu failed), %zu rejected, %s", c.fixes, c.no_fix, c.solves,
                c.failed, c.rejected, c.anchored ? "corrected" : "waiting for fixes");
  return "GNSS" + source + s;
}

}  // namespace roadslam::pipeline

// Rates, gaps and rate over time of one stream of stamps.
#include <algorithm>
#include <cmath>

#include "roadslam/recording_report/recording_report.h"

namespace roadslam::recording_report {

StreamStats streamStats(std::vector<double> t, double nominal_period_s, double start_s, const ReportParams& p) {
  StreamStats s;
  std::sort(t.begin(), t.end());
  s.count = t.size();
  if (t.empty()) return s;
  s.first_s = t.front();
  s.last_s = t.back();
  if (t.size() > 1 && s.last_s > s.first_s) s.rate_hz = static_cast<double>(t.size() - 1) / (s.last_s - s.first_s);
  std::vector<double> dt(t.size() > 1 ? t.size() - 1 : 0);
  for (size_t i = 1; i < t.size(); ++i) dt[i - 1] = t[i] - t[i - 1];
  if (nominal_period_s <= 0 && !dt.empty()) {
    std::vector<double> sorted = dt;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
    nominal_period_s = sorted[sorted.size() / 2];
  }
  s.nominal_period_s = nominal_period_s;
  s.gap_threshold_s = std::max(p.gap_factor * nominal_period_s, p.min_gap_s);
  for (size_t i = 0; i < dt.size(); ++i) {
    if (dt[i] <= s.gap_threshold_s) continue;
    ++s.gap_count;
    s.gap_time_s += dt[i];
    s.gaps.push_back({t[i], t[i + 1]});
  }
  if (s.gaps.size() > p.max_listed_gaps) {  // keep the longest, listed in time order
    std::stable_sort(s.gaps.begin(), s.gaps.end(), [](const Gap& a, const Gap& b) { return a.length() > b.length(); });
    s.gaps.resize(p.max_listed_gaps);
    std::sort(s.gaps.begin(), s.gaps.end(), [](const Gap& a, const Gap& b) { return a.start_s < b.start_s; });
  }
  // Wider bins when the stream would need more than max_rate_bins (a long drive, or streams far apart).
  const double bin = std::max(p.rate_bin_s > 0 ? p.rate_bin_s : 1.0,
                              (s.last_s - start_s) / static_cast<double>(std::max<std::size_t>(p.max_rate_bins, 1)));
  const auto nbins = static_cast<size_t>(std::floor((s.last_s - start_s) / bin)) + 1;
  std::vector<double> counts(nbins, 0.0);
  for (double v : t) counts[std::min(nbins - 1, static_cast<size_t>(std::max(0.0, std::floor((v - start_s) / bin))))] += 1;
  for (size_t i = 0; i < nbins; ++i) {
    // Only whole bins (a part-filled last bin would misstate the rate), unless there is no whole one.
    const double covered = i + 1 < nbins ? bin : s.last_s - start_s - static_cast<double>(i) * bin;
    if (i + 1 == nbins && nbins > 1 && covered < bin) continue;
    s.bin_t_s.push_back(static_cast<double>(i) * bin);
    s.bin_rate_hz.push_back(counts[i] / (i + 1 < nbins ? bin : std::max(covered, 1e-9)));
  }
  return s;
}

}  // namespace roadslam::recording_report

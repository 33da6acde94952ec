#include "roadslam/rawlog/observation_index.h"

#include <algorithm>

namespace roadslam::rawlog {

void TimeOrder::add(uint32_t i, double t_s) {
  if (!std::isfinite(t_s)) return;
  const auto at = std::upper_bound(by_time_.begin(), by_time_.end(), t_s,
                                   [](double t, const std::pair<double, uint32_t>& e) { return t < e.first; });
  by_time_.insert(at, {t_s, i});
}

std::optional<std::size_t> TimeOrder::atTime(double t_s) const {
  if (by_time_.empty()) return std::nullopt;
  const auto it = std::upper_bound(by_time_.begin(), by_time_.end(), t_s,
                                   [](double t, const std::pair<double, uint32_t>& e) { return t < e.first; });
  return it == by_time_.begin() ? by_time_.front().second : (it - 1)->second;
}

std::vector<std::size_t> TimeOrder::inRange(double t0_s, double t1_s) const {
  auto lo = std::lower_bound(by_time_.begin(), by_time_.end(), t0_s,
                             [](const std::pair<double, uint32_t>& e, double t) { return e.first < t; });
  std::vector<std::size_t> out;
  for (; lo != by_time_.end() && lo->first < t1_s; ++lo) out.push_back(lo->second);
  return out;
}

uint16_t NameIds::id(const std::string& s) {
  const auto it = ids_.find(s);
  if (it != ids_.end()) return it->second;
  if (names_.size() >= 0xffff) return 0;
  names_.push_back(s);
  return ids_[s] = uint16_t(names_.size() - 1);
}

void NameIds::clear() {
  names_.clear();
  ids_.clear();
}

}  // namespace roadslam::rawlog

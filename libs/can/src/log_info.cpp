#include <roadslam/can/log_info.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>

namespace roadslam::can {
namespace {
using Key = std::tuple<std::string, bool, std::uint32_t>;  // interface, extended, id

std::string idText(std::uint32_t id, bool ext) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), ext ? "%08X" : "%03X", id);
  return buf;
}
}  // namespace

LogInfo analyzeLog(const std::vector<CanFrame>& frames, const Database* db, double gap_factor, double min_gap_s,
                   std::size_t max_gaps) {
  LogInfo info;
  info.with_dbc = db != nullptr;
  std::map<Key, std::vector<const CanFrame*>> by_id;
  std::int64_t prev = 0;
  for (const CanFrame& f : frames) {
    ++info.frames;
    if (info.frames > 1 && f.t_us < prev) info.non_monotonic = true;
    prev = f.t_us;
    if (f.error()) {
      ++info.error_frames;
      continue;
    }
    if (f.remote()) ++info.remote_frames;
    if (f.fd()) ++info.fd_frames;
    by_id[Key{f.iface.data(), f.extended(), f.id}].push_back(&f);
  }
  if (!frames.empty()) {
    info.first_s = frames.front().timeSeconds();
    info.last_s = frames.back().timeSeconds();
  }
  for (const auto& [key, list] : by_id) {
    IdInfo r;
    std::tie(r.iface, r.extended, r.id) = key;
    r.count = list.size();
    r.first_s = list.front()->timeSeconds();
    r.last_s = list.back()->timeSeconds();
    if (r.count > 1 && r.last_s > r.first_s) r.rate_hz = static_cast<double>(r.count - 1) / (r.last_s - r.first_s);
    std::vector<double> dt;
    for (std::size_t i = 1; i < list.size(); ++i) dt.push_back(list[i]->timeSeconds() - list[i - 1]->timeSeconds());
    if (!dt.empty()) {
      std::vector<double> sorted = dt;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
      r.median_period_s = sorted[sorted.size() / 2];
      r.max_period_s = *std::max_element(dt.begin(), dt.end());
      for (std::size_t i = 0; i < dt.size(); ++i) {
        if (dt[i] > gap_factor * r.median_period_s && dt[i] > min_gap_s) {
          ++r.gaps;
          info.gaps.push_back({r.iface, r.id, r.extended, list[i + 1]->timeSeconds(), dt[i], r.median_period_s});
        }
      }
    }
    const Message* m = db ? db->findMessage(r.id | (r.extended ? 0x80000000U : 0U)) : nullptr;
    r.in_dbc = m != nullptr;
    if (m) r.name = m->name;
    for (const CanFrame* f : list) {
      r.min_len = std::min(r.min_len, f->len);
      r.max_len = std::max(r.max_len, f->len);
      if (m && !f->remote() && f->len != m->size) ++r.dlc_mismatches;
    }
    if (db && !m) {
      ++info.unknown_ids;
      info.unknown_frames += r.count;
    }
    info.dlc_mismatch_frames += r.dlc_mismatches;
    info.ids.push_back(r);
  }
  std::sort(info.gaps.begin(), info.gaps.end(),
            [](const TimingGap& a, const TimingGap& b) { return a.length_s > b.length_s; });
  if (info.gaps.size() > max_gaps) info.gaps.resize(max_gaps);
  return info;
}

std::string formatLogInfoText(const LogInfo& in) {
  std::ostringstream o;
  char buf[256];
  std::snprintf(buf, sizeof(buf), "%zu frames, %.3f s, %zu ids; %zu error, %zu remote, %zu FD frames%s\n", in.frames,
                in.last_s - in.first_s, in.ids.size(), in.error_frames, in.remote_frames, in.fd_frames,
                in.non_monotonic ? "; TIMESTAMPS NOT MONOTONIC" : "");
  o << buf;
  if (in.with_dbc) {
    std::snprintf(buf, sizeof(buf), "DBC: %zu unknown ids (%zu frames), %zu frames with a DLC mismatch\n",
                  in.unknown_ids, in.unknown_frames, in.dlc_mismatch_frames);
    o << buf;
  }
  o << "iface id        count   rate_Hz  median_ms  max_ms  gaps  len    dbc\n";
  for (const IdInfo& r : in.ids) {
    std::snprintf(buf, sizeof(buf), "%-5s %-8s %7zu %9.2f %10.2f %7.1f %5zu  %u-%u  %s%s\n", r.iface.c_str(),
                  idText(r.id, r.extended).c_str(), r.count, r.rate_hz, r.median_period_s * 1e3, r.max_period_s * 1e3,
                  r.gaps, r.min_len, r.max_len,
                  !in.with_dbc ? "" : (r.in_dbc ? r.name.c_str() : "UNKNOWN"),
                  r.dlc_mismatches ? (" DLC-MISMATCH x" + std::to_string(r.dlc_mismatches)).c_str() : "");
    o << buf;
  }
  if (!in.gaps.empty()) o << "largest gaps:\n";
  for (const TimingGap& g : in.gaps) {
    std::snprintf(buf, sizeof(buf), "  %s %s at %.6f: %.3f s (period %.1f ms)\n", g.iface.c_str(),
                  idText(g.id, g.extended).c_str(), g.t_s, g.length_s, g.expected_s * 1e3);
    o << buf;
  }
  return o.str();
}

std::string formatLogInfoJson(const LogInfo& in) {
  nlohmann::json j;
  j["frames"] = in.frames;
  j["duration_s"] = in.last_s - in.first_s;
  j["error_frames"] = in.error_frames;
  j["remote_frames"] = in.remote_frames;
  j["fd_frames"] = in.fd_frames;
  j["non_monotonic"] = in.non_monotonic;
  if (in.with_dbc) {
    j["unknown_ids"] = in.unknown_ids;
    j["unknown_frames"] = in.unknown_frames;
    j["dlc_mismatch_frames"] = in.dlc_mismatch_frames;
  }
  j["ids"] = nlohmann::json::array();
  for (const IdInfo& r : in.ids) {
    nlohmann::json e{{"iface", r.iface},   {"id", idText(r.id, r.extended)}, {"count", r.count},
                     {"rate_hz", r.rate_hz}, {"median_period_s", r.median_period_s},
                     {"max_period_s", r.max_period_s}, {"gaps", r.gaps}, {"min_len", r.min_len},
                     {"max_len", r.max_len}};
    if (in.with_dbc) {
      e["in_dbc"] = r.in_dbc;
      e["name"] = r.name;
      e["dlc_mismatches"] = r.dlc_mismatches;
    }
    j["ids"].push_back(e);
  }
  j["gaps"] = nlohmann::json::array();
  for (const TimingGap& g : in.gaps) {
    j["gaps"].push_back({{"iface", g.iface}, {"id", idText(g.id, g.extended)}, {"t_s", g.t_s},
                         {"length_s", g.length_s}, {"expected_s", g.expected_s}});
  }
  return j.dump(1);
}

}  // namespace roadslam::can

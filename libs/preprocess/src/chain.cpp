#include "roadslam/preprocess/chain.h"

#include "param_utils.h"
#include "roadslam/common/param_table.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace roadslam::preprocess {
namespace {
const char* const kNonFinite = "non_finite";

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::string tok;
  std::istringstream ss(s);
  while (std::getline(ss, tok, ',')) {
    tok.erase(0, tok.find_first_not_of(" \t"));
    tok.erase(tok.find_last_not_of(" \t") + 1);
    if (!tok.empty()) out.push_back(tok);
  }
  return out;
}

/// Every key of the section: the chain's own (with the thesis alias skipF), then each filter's table.
const std::vector<std::string>& knownKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k{"filters"};
    for (const auto& part : {fieldKeys<PreprocessParams>(), fieldKeys<EgoParams>(), fieldKeys<RangeParams>(),
                             fieldKeys<RoiParams>(), fieldKeys<RansacGroundParams>(), std::vector<std::string>{"ransac_up"},
                             fieldKeys<GroundSegParams>(), fieldKeys<RandomDownsampleParams>(), fieldKeys<VoxelParams>(),
                             fieldKeys<SorParams>()})
      k.insert(k.end(), part.begin(), part.end());
    return k;
  }();
  return keys;
}
}  // namespace

const std::vector<std::string>& knownFilterNames() {
  static const std::vector<std::string> names{"ego",   "range",  "roi",   "ground_ransac",
                                              "ground_linefit", "random", "voxel", "sor"};
  return names;
}

// The filter list (`filters`, a comma list) is read and written by hand beside the table.
void PreprocessParams::fields(ParamTable& t) { t.numOrAlias("keep_every_n_frames", "skipF", keep_every_n_frames); }

void PreprocessParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  const std::string list = readString(cfg, s, "filters", "");
  if (!list.empty()) filters = splitList(list);
  for (const auto& f : filters) {
    const auto& names = knownFilterNames();
    detail::require(std::find(names.begin(), names.end(), f) != names.end(), s, "filters",
                    "unknown filter '" + f + "'");
  }
  loadFields(*this, cfg, s);
  detail::require(keep_every_n_frames >= 1, s, "keep_every_n_frames", "must be >= 1");
  ego.loadFromConfigFile(cfg, s);
  range.loadFromConfigFile(cfg, s);
  roi.loadFromConfigFile(cfg, s);
  ransac.loadFromConfigFile(cfg, s);
  ground_seg.loadFromConfigFile(cfg, s);
  random.loadFromConfigFile(cfg, s);
  voxel.loadFromConfigFile(cfg, s);
  sor.loadFromConfigFile(cfg, s);
  unknown_keys = unknownKeys(cfg, s, knownKeys());
}

void PreprocessParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  std::string list;
  for (const auto& f : filters) list += (list.empty() ? "" : ",") + f;
  cfg.write(s, "filters", list);
  saveFields(*this, cfg, s);
  ego.saveToConfigFile(cfg, s);
  range.saveToConfigFile(cfg, s);
  roi.saveToConfigFile(cfg, s);
  ransac.saveToConfigFile(cfg, s);
  ground_seg.saveToConfigFile(cfg, s);
  random.saveToConfigFile(cfg, s);
  voxel.saveToConfigFile(cfg, s);
  sor.saveToConfigFile(cfg, s);
}

std::string formatTotals(const PreprocessTotals& t) {
  std::ostringstream out;
  const size_t processed = t.frames - t.skipped;
  out << "frames: " << t.frames << " (" << t.skipped << " skipped), points " << t.points_in << " -> "
      << t.points_out << '\n';
  out << std::fixed;
  for (const auto& s : t.steps) {
    const double pct = s.points_in ? 100.0 * static_cast<double>(s.removed) / static_cast<double>(s.points_in) : 0.0;
    const double ms = processed ? 1e3 * s.wall_time_s / static_cast<double>(processed) : 0.0;
    out << "  " << s.name << ": " << s.points_in << " in, " << s.removed << " removed ("
        << std::setprecision(1) << pct << " %), " << std::setprecision(3) << ms << " ms/frame\n";
  }
  return out.str();
}

PreprocessChain::PreprocessChain(PreprocessParams params) : params_(std::move(params)) {
  const auto& names = knownFilterNames();
  for (const auto& f : params_.filters) {
    if (std::find(names.begin(), names.end(), f) == names.end())
      throw std::invalid_argument("PreprocessChain: unknown filter '" + f + "'");
  }
  if (params_.keep_every_n_frames < 1) throw std::invalid_argument("keep_every_n_frames must be >= 1");
  totals_.steps.push_back({kNonFinite, 0, 0, 0});
  for (const auto& f : params_.filters) totals_.steps.push_back({f, 0, 0, 0});
}

size_t PreprocessChain::applyStep(const std::string& name, std::vector<ScanPoint>& pts) const {
  if (name == "ego") return removeEgo(pts, params_.ego);
  if (name == "range") return removeOutOfRange(pts, params_.range);
  if (name == "roi") return removeOutsideRoi(pts, params_.roi);
  if (name == "ground_ransac") return removeGroundRansac(pts, params_.ransac);
  if (name == "ground_linefit") return removeGroundLinefit(pts, params_.ground_seg);
  if (name == "voxel") return voxelDownsample(pts, params_.voxel);
  if (name == "sor") return removeStatisticalOutliers(pts, params_.sor);
  if (name == "random") {
    RandomDownsampleParams p = params_.random;
    p.seed += next_frame_;  // a different, reproducible draw per frame
    return randomDownsample(pts, p);
  }
  return 0;  // unreachable: names checked in the constructor
}

PreprocessReport PreprocessChain::process(Scan& scan) {
  using Clock = std::chrono::steady_clock;
  PreprocessReport rep;
  rep.frame_index = next_frame_;
  rep.points_in = scan.points.size();
  ++totals_.frames;
  if (next_frame_ % static_cast<size_t>(params_.keep_every_n_frames) != 0) {
    rep.skipped = true;
    rep.points_out = rep.points_in;
    ++totals_.skipped;
    ++next_frame_;
    return rep;
  }
  totals_.points_in += rep.points_in;
  const auto t_start = Clock::now();
  for (size_t i = 0; i < totals_.steps.size(); ++i) {
    const std::string& name = totals_.steps[i].name;
    FilterStepReport step{name, scan.points.size(), 0, 0};
    const auto t0 = Clock::now();
    step.removed = i == 0 ? removeNonFinite(scan.points) : applyStep(name, scan.points);
    step.wall_time_s = std::chrono::duration<double>(Clock::now() - t0).count();
    totals_.steps[i].points_in += step.points_in;
    totals_.steps[i].removed += step.removed;
    totals_.steps[i].wall_time_s += step.wall_time_s;
    rep.steps.push_back(step);
  }
  rep.wall_time_s = std::chrono::duration<double>(Clock::now() - t_start).count();
  rep.points_out = scan.points.size();
  totals_.points_out += rep.points_out;
  ++next_frame_;
  return rep;
}

}  // namespace roadslam::preprocess

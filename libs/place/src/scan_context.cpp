#include "roadslam/place/scan_context.h"

#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "roadslam/common/config.h"
#include "roadslam/common/param_table.h"

namespace roadslam::place {
namespace {

struct RingKeyAdaptor {
  const std::vector<ScanContext>* d = nullptr;
  size_t n = 0;
  size_t kdtree_get_point_count() const { return n; }
  float kdtree_get_pt(size_t i, size_t k) const { return (*d)[i].ring_key[static_cast<Eigen::Index>(k)]; }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const { return false; }
};
using RingKeyTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, RingKeyAdaptor>,
                                                        RingKeyAdaptor, -1, uint32_t>;

constexpr size_t kRebuildEvery = 50;  // kd-tree rebuilt when this many eligible entries are not in it

}  // namespace

void ScanContextParams::fields(ParamTable& t) {
  t.num("num_rings", num_rings);
  t.num("num_sectors", num_sectors);
  t.num("max_radius_m", max_radius_m);
  t.num("height_offset_m", height_offset_m);
  t.num("ring_key_candidates", ring_key_candidates);
  t.num("max_distance", max_distance);
  t.num("min_travel_m", min_travel_m);
}

void ScanContextParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  rejectUnknownKeys(cfg, s, fieldKeys<ScanContextParams>());
  if (num_rings < 1 || num_sectors < 4 || max_radius_m <= 0 || ring_key_candidates < 1 || max_distance <= 0) {
    throw std::runtime_error("[" + s + "]: num_rings >= 1, num_sectors >= 4, max_radius_m > 0, ring_key_candidates >= 1, "
                             "max_distance > 0 required");
  }
}

void ScanContextParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

// Kim & Kim 2018 Sec. III-A: bin (i, j) holds the maximum height of the points in ring i, sector j (eq. 1-2).
ScanContext makeScanContext(const std::vector<Eigen::Vector3d>& pts, const ScanContextParams& p) {
  ScanContext sc;
  sc.bins = Eigen::MatrixXf::Zero(p.num_rings, p.num_sectors);
  for (const auto& q : pts) {
    if (!q.allFinite()) continue;
    const double r = std::hypot(q.x(), q.y());
    if (r >= p.max_radius_m || r <= 0) continue;
    const int ring = std::min(p.num_rings - 1, static_cast<int>(r / p.max_radius_m * p.num_rings));
    const double a = (std::atan2(q.y(), q.x()) + M_PI) / (2 * M_PI);
    const int sector = std::clamp(static_cast<int>(a * p.num_sectors), 0, p.num_sectors - 1);
    float& b = sc.bins(ring, sector);
    b = std::max(b, static_cast<float>(std::max(0.0, q.z() + p.height_offset_m)));
  }
  sc.ring_key = sc.bins.rowwise().mean();
  return sc;
}

// Eq. 5-6: mean cosine distance of the columns, minimised over column shifts.
double scanContextDistance(const ScanContext& a, const ScanContext& b, int* shift) {
  const Eigen::Index ns = a.bins.cols();
  if (b.bins.cols() != ns || b.bins.rows() != a.bins.rows() || ns == 0) return 1.0;
  const Eigen::VectorXf na = a.bins.colwise().norm(), nb = b.bins.colwise().norm();
  double best = 1.0;
  int best_s = 0;
  for (Eigen::Index s = 0; s < ns; ++s) {
    double sum = 0;
    int n = 0;
    for (Eigen::Index j = 0; j < ns; ++j) {
      const Eigen::Index k = (j + s) % ns;
      if (na[j] <= 0 || nb[k] <= 0) continue;
      sum += a.bins.col(j).dot(b.bins.col(k)) / (na[j] * nb[k]);
      ++n;
    }
    const double d = n > 0 ? 1.0 - sum / n : 1.0;
    if (d < best) {
      best = d;
      best_s = static_cast<int>(s);
    }
  }
  if (shift) *shift = best_s;
  return best;
}

struct ScanContextDatabase::Index {
  RingKeyAdaptor ad;
  std::unique_ptr<RingKeyTree> tree;
};

ScanContextDatabase::ScanContextDatabase(ScanContextParams p) : p_(p) {}
ScanContextDatabase::~ScanContextDatabase() = default;
ScanContextDatabase::ScanContextDatabase(ScanContextDatabase&&) noexcept = default;
ScanContextDatabase& ScanContextDatabase::operator=(ScanContextDatabase&&) noexcept = default;

size_t ScanContextDatabase::add(size_t id, double path_m, ScanContext sc) {
  descs_.push_back(std::move(sc));
  ids_.push_back(id);
  path_m_.push_back(path_m);
  index_.reset();  // the adaptor's vector may have moved
  indexed_ = 0;
  return descs_.size() - 1;
}
size_t ScanContextDatabase::size() const { return descs_.size(); }
const ScanContext& ScanContextDatabase::descriptor(size_t i) const { return descs_.at(i); }
size_t ScanContextDatabase::idAt(size_t i) const { return ids_.at(i); }

std::vector<PlaceMatch> ScanContextDatabase::query(const ScanContext& sc, double path_m, int max_matches) const {
  // eligible: entries driven at least min_travel_m before (paths grow with the index within a drive)
  size_t eligible = 0;
  while (eligible < descs_.size() && path_m - path_m_[eligible] >= p_.min_travel_m) ++eligible;
  if (eligible == 0) return {};
  if (!index_ || eligible > indexed_ + kRebuildEvery || eligible < indexed_) {
    index_ = std::make_unique<Index>();
    index_->ad = RingKeyAdaptor{&descs_, eligible};
    index_->tree = std::make_unique<RingKeyTree>(static_cast<int>(sc.ring_key.size()), index_->ad,
                                                 nanoflann::KDTreeSingleIndexAdaptorParams(10));
    index_->tree->buildIndex();
    indexed_ = eligible;
  }
  // candidates: nearest ring keys in the tree, plus the eligible entries added since its build
  const size_t k = std::min(static_cast<size_t>(p_.ring_key_candidates), indexed_);
  std::vector<uint32_t> idx(k);
  std::vector<float> d2(k);
  const size_t found = k > 0 ? index_->tree->knnSearch(sc.ring_key.data(), k, idx.data(), d2.data()) : 0;
  std::vector<size_t> cand(idx.begin(), idx.begin() + static_cast<long>(found));
  for (size_t i = indexed_; i < eligible; ++i) cand.push_back(i);
  std::vector<PlaceMatch> out;
  for (size_t c : cand) {
    int shift = 0;
    const double d = scanContextDistance(sc, descs_[c], &shift);
    if (d >= p_.max_distance) continue;
    double yaw = shift * 2 * M_PI / p_.num_sectors;
    if (yaw > M_PI) yaw -= 2 * M_PI;
    out.push_back({ids_[c], d, yaw});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.distance < b.distance; });
  if (out.size() > static_cast<size_t>(max_matches)) out.resize(static_cast<size_t>(max_matches));
  return out;
}

}  // namespace roadslam::place

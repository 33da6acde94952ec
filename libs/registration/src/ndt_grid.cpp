#include "ndt_grid.h"

#include <Eigen/Eigenvalues>

#include <algorithm>

namespace roadslam::registration {
namespace {

/// Point sums of one voxel: n, sum p, sum p p^T (upper triangle). Sums add across voxels, so a
/// coarse level is the sum of its eight children (no second pass over the points).
struct Acc {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
  int n = 0;
  void add(const Eigen::Vector3d& p) {
    sum += p;
    xx += p.x() * p.x();
    xy += p.x() * p.y();
    xz += p.x() * p.z();
    yy += p.y() * p.y();
    yz += p.y() * p.z();
    zz += p.z() * p.z();
    ++n;
  }
  void add(const Acc& o) {
    sum += o.sum;
    xx += o.xx, xy += o.xy, xz += o.xz, yy += o.yy, yz += o.yz, zz += o.zz;
    n += o.n;
  }
};

// Mean and sample covariance, eigenvalues clamped to >= 0.01 of the largest (Magnusson 2009,
// Sec. 6.2 uses 0.001; PCL 0.01, which keeps the Hessian better conditioned), then inverted.
void finishCell(const Acc& a, int min_pts, NdtCell& c, Eigen::Vector3d& normal) {
  c.valid = false;
  normal.setZero();
  if (a.n < std::max(min_pts, 4)) return;
  c.mean = a.sum / a.n;
  Eigen::Matrix3d sq;
  sq << a.xx, a.xy, a.xz, a.xy, a.yy, a.yz, a.xz, a.yz, a.zz;
  const Eigen::Matrix3d cov = (sq - a.n * c.mean * c.mean.transpose()) / (a.n - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov);
  Eigen::Vector3d ev = es.eigenvalues();
  if (!(ev(2) > 0)) return;
  for (int i = 0; i < 2; ++i) ev(i) = std::max(ev(i), 0.01 * ev(2));
  c.cov_inv = es.eigenvectors() * ev.cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
  normal = es.eigenvectors().col(0);
  c.valid = true;
}

NdtGrid finishGrid(FlatIndex&& index, const std::vector<Acc>& acc, double res_m, int min_pts) {
  NdtGrid g;
  g.resolution_m = res_m;
  g.index = std::move(index);
  g.cells.resize(acc.size());
  g.normals.resize(acc.size());
  for (size_t i = 0; i < acc.size(); ++i) {
    finishCell(acc[i], min_pts, g.cells[i], g.normals[i]);
    g.num_valid += g.cells[i].valid ? 1 : 0;
  }
  return g;
}

}  // namespace

void FlatIndex::rehash(size_t min_slots) {
  size_t n = 16;
  int bits = 4;
  while (n < min_slots) n <<= 1, ++bits;
  std::vector<Slot> old;
  old.swap(slots_);
  slots_.assign(n, Slot{});
  mask_ = n - 1;
  shift_ = 64 - bits;
  for (const Slot& s : old) {
    if (s.key == kEmpty) continue;
    size_t i = slot(s.key);
    while (slots_[i].key != kEmpty) i = (i + 1) & mask_;
    slots_[i] = s;
  }
}

std::vector<NdtGrid> buildNdtGrids(const std::vector<Eigen::Vector3d>& points, double res_m, int levels, int min_pts) {
  // Finest level: one pass, each point added to its voxel's sums; its cell remembered for the buckets.
  FlatIndex index(points.size() / 8 + 16);
  std::vector<Acc> acc;
  acc.reserve(points.size() / 4 + 16);
  std::vector<uint64_t> keys;  // keys[c]: voxel of cell c
  std::vector<int32_t> cell_of(points.size());
  const double inv = 1.0 / res_m;
  for (size_t i = 0; i < points.size(); ++i) {
    bool inserted = false;
    const uint64_t key = voxelKey(points[i], inv);
    const int32_t c = index.findOrInsert(key, inserted);
    if (inserted) acc.emplace_back(), keys.push_back(key);
    acc[static_cast<size_t>(c)].add(points[i]);
    cell_of[i] = c;
  }
  std::vector<NdtGrid> grids(static_cast<size_t>(std::max(levels, 1)));
  // Coarser levels from the finer level's sums.
  std::vector<Acc> fine_acc = acc;
  std::vector<uint64_t> fine_keys = std::move(keys);
  for (size_t l = grids.size() - 1; l-- > 0;) {
    FlatIndex coarse(fine_acc.size() / 4 + 16);
    std::vector<Acc> coarse_acc;
    std::vector<uint64_t> coarse_keys;
    for (size_t i = 0; i < fine_acc.size(); ++i) {
      bool inserted = false;
      const uint64_t k = parentKey(fine_keys[i]);
      const int32_t c = coarse.findOrInsert(k, inserted);
      if (inserted) coarse_acc.emplace_back(), coarse_keys.push_back(k);
      coarse_acc[static_cast<size_t>(c)].add(fine_acc[i]);
    }
    grids[l] = finishGrid(std::move(coarse), coarse_acc, res_m * std::ldexp(1.0, static_cast<int>(grids.size() - 1 - l)),
                          min_pts);
    fine_acc.swap(coarse_acc);
    fine_keys.swap(coarse_keys);
  }
  NdtGrid& finest = grids.back();
  finest = finishGrid(std::move(index), acc, res_m, min_pts);
  // Counting sort of point indices by cell.
  finest.bucket_begin.assign(acc.size() + 1, 0);
  for (const int32_t c : cell_of) ++finest.bucket_begin[static_cast<size_t>(c) + 1];
  for (size_t i = 1; i < finest.bucket_begin.size(); ++i) finest.bucket_begin[i] += finest.bucket_begin[i - 1];
  finest.bucket_points.resize(points.size());
  std::vector<uint32_t> fill(finest.bucket_begin.begin(), finest.bucket_begin.end() - 1);
  for (size_t i = 0; i < points.size(); ++i) {
    finest.bucket_points[fill[static_cast<size_t>(cell_of[i])]++] = static_cast<uint32_t>(i);
  }
  return grids;
}

int nearestInGrid(const NdtGrid& g, const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& x,
                  double max_dist2, double& d2) {
  const Eigen::Vector3d u = x / g.resolution_m;
  const Eigen::Vector3d cf(std::floor(u.x()), std::floor(u.y()), std::floor(u.z()));
  // Squared distance from x to the slab of the neighbour at offset -1, 0, +1 along each axis [m^2]:
  // a neighbour cell whose box is farther than the best point so far is not looked up.
  double gap2[3][3];
  for (int a = 0; a < 3; ++a) {
    const double lo = (u(a) - cf(a)) * g.resolution_m, hi = g.resolution_m - lo;
    gap2[a][0] = lo * lo, gap2[a][1] = 0, gap2[a][2] = hi * hi;
  }
  int best = -1;
  double best_d2 = max_dist2;
  const auto scan = [&](int i, int j, int k) {
    if (gap2[0][i + 1] + gap2[1][j + 1] + gap2[2][k + 1] > best_d2) return;
    const int32_t c = g.index.find(voxelKey(static_cast<int64_t>(cf.x()) + i, static_cast<int64_t>(cf.y()) + j,
                                            static_cast<int64_t>(cf.z()) + k));
    if (c < 0) return;
    for (uint32_t b = g.bucket_begin[static_cast<size_t>(c)]; b < g.bucket_begin[static_cast<size_t>(c) + 1]; ++b) {
      const double dd = (points[g.bucket_points[b]] - x).squaredNorm();
      if (dd <= best_d2) best_d2 = dd, best = static_cast<int>(g.bucket_points[b]);
    }
  };
  scan(0, 0, 0);  // own cell first: its best point prunes most neighbours
  for (int i = -1; i <= 1; ++i) {
    for (int j = -1; j <= 1; ++j) {
      for (int k = -1; k <= 1; ++k) {
        if (i || j || k) scan(i, j, k);
      }
    }
  }
  d2 = best_d2;
  return best;
}

}  // namespace roadslam::registration

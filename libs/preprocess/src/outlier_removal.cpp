#include "param_utils.h"
#include "roadslam/preprocess/downsample.h"
#include "roadslam/common/param_table.h"

#include <nanoflann.hpp>

#include <cmath>

namespace roadslam::preprocess {
namespace {
/// nanoflann dataset adaptor over ScanPoint (x, y, z).
struct ScanAdaptor {
  const std::vector<ScanPoint>& pts;
  size_t kdtree_get_point_count() const { return pts.size(); }
  float kdtree_get_pt(size_t i, size_t dim) const {
    return dim == 0 ? pts[i].x : (dim == 1 ? pts[i].y : pts[i].z);
  }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;
  }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, ScanAdaptor>,
                                                   ScanAdaptor, 3, uint32_t>;
}  // namespace

size_t removeStatisticalOutliers(std::vector<ScanPoint>& pts, const SorParams& prm) {
  const size_t n = pts.size();
  const size_t k = static_cast<size_t>(prm.k) + 1;  // the query point is its own nearest neighbour
  if (n <= k) return 0;
  ScanAdaptor adaptor{pts};
  KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  std::vector<uint32_t> idx(k);
  std::vector<float> d2(k);
  std::vector<float> mean_d(n);
  double sum = 0, sum_sq = 0;
  for (size_t i = 0; i < n; ++i) {
    const float q[3] = {pts[i].x, pts[i].y, pts[i].z};
    const size_t found = tree.knnSearch(q, k, idx.data(), d2.data());
    double s = 0;
    for (size_t j = 1; j < found; ++j) s += std::sqrt(static_cast<double>(d2[j]));
    const double m = found > 1 ? s / static_cast<double>(found - 1) : 0.0;
    mean_d[i] = static_cast<float>(m);
    sum += m, sum_sq += m * m;
  }
  const double mu = sum / static_cast<double>(n);
  const double sigma = std::sqrt(std::max(0.0, sum_sq / static_cast<double>(n) - mu * mu));
  const float thr = static_cast<float>(mu + prm.std_mul * sigma);
  size_t w = 0;
  for (size_t i = 0; i < n; ++i)
    if (mean_d[i] <= thr) pts[w++] = pts[i];
  pts.resize(w);
  return n - w;
}

void SorParams::fields(ParamTable& t) {
  t.num("sor_k", k);
  t.num("sor_std_mul", std_mul);
}

void SorParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(k >= 1 && k <= 100, s, "sor_k", "must be in [1, 100]");
  detail::require(std_mul > 0, s, "sor_std_mul", "must be > 0");
}
void SorParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

}  // namespace roadslam::preprocess

#include "roadslam/preprocess/downsample.h"

#include "param_utils.h"
#include "rng.h"

#include <cmath>

namespace roadslam::preprocess {

size_t randomDownsample(std::vector<ScanPoint>& pts, const RandomDownsampleParams& prm) {
  const size_t n = pts.size();
  size_t need = static_cast<size_t>(std::llround(prm.keep_fraction * static_cast<double>(n)));
  if (need >= n) return 0;
  detail::SplitMix64 rng(prm.seed);
  size_t w = 0;
  for (size_t i = 0; i < n && need > 0; ++i) {
    // Algorithm S: select point i with probability need / (points left).
    if (rng.below(n - i) < need) {
      pts[w++] = pts[i];
      --need;
    }
  }
  pts.resize(w);
  return n - w;
}

VoxelKey voxelOf(const ScanPoint& pt, double voxel_size_m) {
  const double inv = 1.0 / voxel_size_m;
  return {static_cast<int32_t>(std::floor(pt.x * inv)), static_cast<int32_t>(std::floor(pt.y * inv)),
          static_cast<int32_t>(std::floor(pt.z * inv))};
}

namespace {
uint64_t packKey(const VoxelKey& k) {
  // 21 bits per axis: +-1,048,576 voxels, i.e. +-52 km at 5 cm.
  constexpr uint64_t mask = (1ull << 21) - 1;
  return ((static_cast<uint64_t>(k.ix) & mask) << 42) | ((static_cast<uint64_t>(k.iy) & mask) << 21) |
         (static_cast<uint64_t>(k.iz) & mask);
}
uint64_t hashKey(uint64_t k) {  // SplitMix64 finaliser as a mixer
  k = (k ^ (k >> 30)) * 0xBF58476D1CE4E5B9ull;
  k = (k ^ (k >> 27)) * 0x94D049BB133111EBull;
  return k ^ (k >> 31);
}
struct Acc {
  double x, y, z, i;
  uint32_t n, first;
};
}  // namespace

size_t voxelDownsample(std::vector<ScanPoint>& pts, const VoxelParams& prm) {
  const size_t n = pts.size();
  if (n == 0) return 0;
  size_t cap = 16;
  while (cap < 2 * n) cap <<= 1;  // load factor <= 0.5 for short linear probes
  std::vector<uint64_t> keys(cap);
  std::vector<int32_t> slot(cap, -1);  // index into voxels
  std::vector<Acc> voxels;
  voxels.reserve(n / 4 + 16);
  const float inv = static_cast<float>(1.0 / prm.voxel_size_m);
  for (size_t i = 0; i < n; ++i) {
    const ScanPoint& p = pts[i];
    const VoxelKey vk{static_cast<int32_t>(std::floor(p.x * inv)), static_cast<int32_t>(std::floor(p.y * inv)),
                      static_cast<int32_t>(std::floor(p.z * inv))};
    const uint64_t key = packKey(vk);
    size_t h = hashKey(key) & (cap - 1);
    while (slot[h] >= 0 && keys[h] != key) h = (h + 1) & (cap - 1);
    if (slot[h] < 0) {
      keys[h] = key;
      slot[h] = static_cast<int32_t>(voxels.size());
      voxels.push_back({p.x, p.y, p.z, p.intensity, 1, static_cast<uint32_t>(i)});
    } else if (prm.mode == VoxelParams::Mode::Centroid) {
      Acc& a = voxels[static_cast<size_t>(slot[h])];
      a.x += p.x, a.y += p.y, a.z += p.z, a.i += p.intensity, ++a.n;
    }
  }
  for (size_t v = 0; v < voxels.size(); ++v) {
    const Acc& a = voxels[v];
    ScanPoint out = pts[a.first];  // a.first >= v: never overwritten before it is read
    if (prm.mode == VoxelParams::Mode::Centroid) {
      const double k = 1.0 / a.n;
      out.x = static_cast<float>(a.x * k), out.y = static_cast<float>(a.y * k);
      out.z = static_cast<float>(a.z * k), out.intensity = static_cast<float>(a.i * k);
    }
    pts[v] = out;
  }
  pts.resize(voxels.size());
  return n - voxels.size();
}

void RandomDownsampleParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                const std::string& s) {
  keep_fraction = detail::readDoubleAlias(cfg, s, "random_keep_fraction", "downS", keep_fraction);
  seed = static_cast<uint64_t>(readInt(cfg, s, "random_seed", static_cast<int>(seed)));
  detail::require(keep_fraction > 0 && keep_fraction <= 1, s, "random_keep_fraction", "must be in (0, 1]");
}
void RandomDownsampleParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  cfg.write(s, "random_keep_fraction", keep_fraction);
  cfg.write(s, "random_seed", static_cast<int>(seed));
}

void VoxelParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  voxel_size_m = readDouble(cfg, s, "voxel_size_m", voxel_size_m);
  const std::string m = readString(cfg, s, "voxel_mode", mode == Mode::Centroid ? "centroid" : "first");
  detail::require(m == "centroid" || m == "first", s, "voxel_mode", "'" + m + "' is not centroid|first");
  mode = m == "centroid" ? Mode::Centroid : Mode::First;
  detail::require(voxel_size_m >= 0.01, s, "voxel_size_m", "must be >= 0.01");
}
void VoxelParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  cfg.write(s, "voxel_size_m", voxel_size_m);
  cfg.write(s, "voxel_mode", std::string(mode == Mode::Centroid ? "centroid" : "first"));
}

}  // namespace roadslam::preprocess

#include "roadslam/preprocess/downsample.h"

#include "param_utils.h"
#include "rng.h"
#include "roadslam/common/param_table.h"

#include <algorithm>
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
    if (rng.uniform() * static_cast<double>(n - i) < static_cast<double>(need)) {
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
/// floor() without the libm call (x86-64 baseline has no SSE4.1 round instruction); exact for
/// |x| < 2^31, which packKey's 21-bit range is far inside of.
inline int32_t fastFloor(float x) {
  const auto i = static_cast<int32_t>(x);
  return i - (static_cast<float>(i) > x);
}

/// Voxel coordinates beyond +-2^20 would alias in packKey's 21 bits: such points (and NaN / inf)
/// are dropped and counted as removed.
constexpr float kMaxCell = 1048575.f;

struct Acc {
  double x, y, z, i;
  uint32_t n, first;
};

/// Open-addressing hash map voxel key -> index into the voxel list; linear probing, grown at a
/// load factor of 1/2. Key, index and a generation stamp share one 16-byte slot, so a lookup touches
/// one cache line and clear() is O(1): slots of older generations count as empty. Kept per thread
/// and reused, so a steady stream of sweeps allocates (and page-faults) nothing.
class VoxelIndex {
 public:
  void clear() {
    size_ = 0;
    if (++gen_ == 0) {  // stamp wrapped: really clear once every 2^32 calls
      std::fill(slots_.begin(), slots_.end(), Slot{});
      gen_ = 1;
    }
  }
  /// Index stored for \p key, or inserts \p next_index and returns -1.
  int32_t findOrInsert(uint64_t key, int32_t next_index) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    const size_t mask = slots_.size() - 1;
    for (size_t h = hashKey(key) & mask;; h = (h + 1) & mask) {
      Slot& s = slots_[h];
      if (s.gen != gen_) {
        s = {key, next_index, gen_};
        ++size_;
        return -1;
      }
      if (s.key == key) return s.index;
    }
  }

 private:
  struct Slot {
    uint64_t key = 0;
    int32_t index = -1;
    uint32_t gen = 0;
  };
  void grow() {
    std::vector<Slot> old(std::max<size_t>(1024, slots_.size() * 2));
    old.swap(slots_);
    const size_t mask = slots_.size() - 1;
    for (const Slot& s : old) {
      if (s.gen != gen_) continue;
      size_t h = hashKey(s.key) & mask;
      while (slots_[h].gen == gen_) h = (h + 1) & mask;
      slots_[h] = s;
    }
  }
  std::vector<Slot> slots_;
  size_t size_ = 0;
  uint32_t gen_ = 1;
};
}  // namespace

size_t voxelDownsample(std::vector<ScanPoint>& pts, const VoxelParams& prm) {
  const size_t n = pts.size();
  if (n == 0) return 0;
  thread_local VoxelIndex index;
  thread_local std::vector<Acc> voxels;
  index.clear();
  voxels.clear();
  const float inv = static_cast<float>(1.0 / prm.voxel_size_m);
  const bool centroid = prm.mode == VoxelParams::Mode::Centroid;
  uint64_t last_key = 0;
  int32_t last_voxel = -1;  // consecutive returns often share a voxel: skip the lookup
  for (size_t i = 0; i < n; ++i) {
    const ScanPoint& p = pts[i];
    const float fx = p.x * inv, fy = p.y * inv, fz = p.z * inv;
    if (!(std::abs(fx) < kMaxCell && std::abs(fy) < kMaxCell && std::abs(fz) < kMaxCell)) continue;
    const uint64_t key = packKey({fastFloor(fx), fastFloor(fy), fastFloor(fz)});
    int32_t v = (last_voxel >= 0 && key == last_key)
                    ? last_voxel
                    : index.findOrInsert(key, static_cast<int32_t>(voxels.size()));
    if (v < 0) {
      v = static_cast<int32_t>(voxels.size());
      voxels.push_back({p.x, p.y, p.z, p.intensity, 1, static_cast<uint32_t>(i)});
    } else if (centroid) {
      Acc& a = voxels[static_cast<size_t>(v)];
      a.x += p.x, a.y += p.y, a.z += p.z, a.i += p.intensity, ++a.n;
    }
    last_key = key, last_voxel = v;
  }
  for (size_t v = 0; v < voxels.size(); ++v) {
    const Acc& a = voxels[v];
    ScanPoint out = pts[a.first];  // a.first >= v: never overwritten before it is read
    if (centroid) {
      const double k = 1.0 / a.n;
      out.x = static_cast<float>(a.x * k), out.y = static_cast<float>(a.y * k);
      out.z = static_cast<float>(a.z * k), out.intensity = static_cast<float>(a.i * k);
    }
    pts[v] = out;
  }
  pts.resize(voxels.size());
  return n - voxels.size();
}

void RandomDownsampleParams::fields(ParamTable& t) {
  t.numOrAlias("random_keep_fraction", "downS", keep_fraction);
  t.num("random_seed", seed);
}

void RandomDownsampleParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(keep_fraction > 0 && keep_fraction <= 1, s, "random_keep_fraction", "must be in (0, 1]");
}
void RandomDownsampleParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

namespace {
const NameTable<VoxelParams::Mode>& voxelModeNames() {
  static const NameTable<VoxelParams::Mode> t{{VoxelParams::Mode::Centroid, "centroid"}, {VoxelParams::Mode::First, "first"}};
  return t;
}
}  // namespace

void VoxelParams::fields(ParamTable& t) {
  t.num("voxel_size_m", voxel_size_m);
  t.choice("voxel_mode", mode, voxelModeNames());
}

void VoxelParams::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg, const std::string& s) {
  loadFields(*this, cfg, s);
  detail::require(voxel_size_m >= 0.01, s, "voxel_size_m", "must be >= 0.01");
}
void VoxelParams::saveToConfigFile(mrpt::config::CConfigFileBase& cfg, const std::string& s) const {
  saveFields(*this, cfg, s);
}

}  // namespace roadslam::preprocess

#include "octo_grid.h"

#include <cstring>

namespace roadslam::mapping::detail {
namespace {

constexpr uint64_t kEmpty = ~uint64_t{0};
constexpr size_t kInitialSlots = 1024;

size_t slotOf(uint64_t key, size_t mask) {
  // Fibonacci hashing: block keys of neighbouring blocks differ in few low bits
  return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> 20) & mask;
}

}  // namespace

VoxelGrid::VoxelGrid(LogOddsModel model) : model_(model) { clear(); }

void VoxelGrid::clear() {
  pages_.clear();
  block_keys_.clear();
  slots_.assign(kInitialSlots, Slot{kEmpty, 0});
  known_ = 0;
  scan_ = 0;
}

VoxelBlock& VoxelGrid::blockOf(uint64_t bk) {
  const size_t mask = slots_.size() - 1;
  for (size_t s = slotOf(bk, mask);; s = (s + 1) & mask) {
    Slot& slot = slots_[s];
    if (slot.key == bk) {
      VoxelBlock& b = block(slot.block);
      if (b.scan != scan_) {
        std::memset(b.touched, 0, sizeof(b.touched));
        b.scan = scan_;
      }
      return b;
    }
    if (slot.key != kEmpty) continue;
    const size_t i = block_keys_.size();
    if ((i >> kPageBits) == pages_.size()) {  // value-initialised: unknown, untouched
      pages_.push_back(std::make_unique<VoxelBlock[]>(size_t{1} << kPageBits));
    }
    slot = Slot{bk, static_cast<uint32_t>(i)};
    block_keys_.push_back(bk);
    if (2 * block_keys_.size() > slots_.size()) grow();
    VoxelBlock& b = block(i);
    b.scan = scan_;
    return b;
  }
}

void VoxelGrid::grow() {
  std::vector<Slot> slots(2 * slots_.size(), Slot{kEmpty, 0});
  const size_t mask = slots.size() - 1;
  for (uint32_t i = 0; i < block_keys_.size(); ++i) {
    size_t s = slotOf(block_keys_[i], mask);
    while (slots[s].key != kEmpty) s = (s + 1) & mask;
    slots[s] = Slot{block_keys_[i], i};
  }
  slots_.swap(slots);
}

void VoxelGrid::set(const octomap::OcTreeKey& k, float log_odds) {
  VoxelBlock& b = blockOf(blockKey(k));
  const unsigned i = voxelIndex(k), w = i >> 6;
  const uint64_t bit = uint64_t{1} << (i & 63);
  if (!(b.known[w] & bit)) ++known_;
  b.known[w] |= bit;
  b.log_odds[i] = log_odds;
}

void VoxelGrid::forEachKnown(const std::function<void(const octomap::OcTreeKey&, float)>& fn) const {
  constexpr unsigned s = VoxelBlock::kBits, w = 16 - VoxelBlock::kBits, m = VoxelBlock::kSide - 1;
  constexpr uint64_t field = (uint64_t{1} << w) - 1;
  for (size_t bi = 0; bi < block_keys_.size(); ++bi) {
    const VoxelBlock& b = block(bi);
    const uint64_t bk = block_keys_[bi];
    const unsigned bx = static_cast<unsigned>(bk & field) << s, by = static_cast<unsigned>((bk >> w) & field) << s,
                   bz = static_cast<unsigned>((bk >> (2 * w)) & field) << s;
    for (unsigned i = 0; i < VoxelBlock::kVoxels; ++i) {
      if (!(b.known[i >> 6] >> (i & 63) & 1)) continue;
      const octomap::OcTreeKey k(static_cast<uint16_t>(bx | (i & m)), static_cast<uint16_t>(by | ((i >> s) & m)),
                                 static_cast<uint16_t>(bz | (i >> (2 * s))));
      fn(k, b.log_odds[i]);
    }
  }
}

size_t VoxelGrid::memoryBytes() const {
  return (pages_.size() << kPageBits) * sizeof(VoxelBlock) + block_keys_.capacity() * sizeof(uint64_t) +
         slots_.capacity() * sizeof(Slot);
}

}  // namespace roadslam::mapping::detail

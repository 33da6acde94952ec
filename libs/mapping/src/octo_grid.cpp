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
  blocks_.clear();
  block_keys_.clear();
  slot_key_.assign(kInitialSlots, kEmpty);
  slot_block_.assign(kInitialSlots, 0);
  known_ = 0;
  scan_ = 0;
  last_key_ = kEmpty;
  last_ = nullptr;
}

void VoxelGrid::beginScan() {
  ++scan_;
  last_key_ = kEmpty;  // the cached block's touched mask belongs to the previous scan
}

VoxelBlock& VoxelGrid::findOrCreate(uint64_t bk) {
  const size_t mask = slot_key_.size() - 1;
  for (size_t s = slotOf(bk, mask);; s = (s + 1) & mask) {
    if (slot_key_[s] == bk) {
      VoxelBlock& b = blocks_[slot_block_[s]];
      if (b.scan != scan_) {
        std::memset(b.touched, 0, sizeof(b.touched));
        b.scan = scan_;
      }
      return b;
    }
    if (slot_key_[s] != kEmpty) continue;
    slot_key_[s] = bk;
    slot_block_[s] = static_cast<uint32_t>(blocks_.size());
    blocks_.emplace_back();
    block_keys_.push_back(bk);
    VoxelBlock& b = blocks_.back();  // value-initialised: unknown, untouched
    b.scan = scan_;
    if (2 * blocks_.size() > slot_key_.size()) {  // load factor <= 1/2 keeps probes short
      grow();
      return blocks_.back();
    }
    return b;
  }
}

void VoxelGrid::grow() {
  const size_t n = 2 * slot_key_.size(), mask = n - 1;
  slot_key_.assign(n, kEmpty);
  slot_block_.assign(n, 0);
  for (uint32_t i = 0; i < block_keys_.size(); ++i) {
    size_t s = slotOf(block_keys_[i], mask);
    while (slot_key_[s] != kEmpty) s = (s + 1) & mask;
    slot_key_[s] = block_keys_[i];
    slot_block_[s] = i;
  }
}

void VoxelGrid::set(const octomap::OcTreeKey& k, float log_odds) {
  VoxelBlock& b = block(k);
  const unsigned i = voxelIndex(k), w = i >> 6;
  const uint64_t bit = uint64_t{1} << (i & 63);
  if (!(b.known[w] & bit)) ++known_;
  b.known[w] |= bit;
  b.log_odds[i] = log_odds;
}

void VoxelGrid::forEachKnown(const std::function<void(const octomap::OcTreeKey&, float)>& fn) const {
  constexpr unsigned s = VoxelBlock::kBits, w = 16 - VoxelBlock::kBits, m = VoxelBlock::kSide - 1;
  constexpr uint64_t field = (uint64_t{1} << w) - 1;
  for (size_t bi = 0; bi < blocks_.size(); ++bi) {
    const VoxelBlock& b = blocks_[bi];
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
  return blocks_.capacity() * sizeof(VoxelBlock) + block_keys_.capacity() * sizeof(uint64_t) +
         slot_key_.capacity() * sizeof(uint64_t) + slot_block_.capacity() * sizeof(uint32_t);
}

}  // namespace roadslam::mapping::detail

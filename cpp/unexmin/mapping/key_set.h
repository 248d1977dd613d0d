// The set of voxels one cloud touches, each once (a free voxel of one ray that is the endpoint of another
// counts as occupied: occupied wins). Keys are OctoMap keys of a 16-level tree, held as their Morton codes so
// that the sorted set visits the tree depth-first. Knows no ROS.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <octomap/OcTreeKey.h>  // after <cstdint>: it uses uint16_t without including it

namespace unexmin {
namespace mapping {

/// The 16 bits of v spread to every third bit of 48 (bit i to bit 3i).
uint64_t spreadBits(uint16_t v);
/// Morton code of a key: bits of z, y, x interleaved, the root's child index in the top 3 bits (of 48).
/// (code >> 3 * (15 - depth)) & 7 is the child index OctoMap's computeChildIdx gives at that depth.
inline uint64_t mortonCode(const octomap::OcTreeKey& key) {
  return spreadBits(key[0]) | (spreadBits(key[1]) << 1) | (spreadBits(key[2]) << 2);
}

/// The bits of axis 0's key in a Morton code (axis i: shifted left by i).
constexpr uint64_t kMortonAxisBits = 0x249249249249ull;
/// Open-addressing hash set of Morton codes with one "occupied" bit each; clear() costs the number of
/// entries, not the capacity, so one set serves every cloud.
class KeySet {
public:
  KeySet();

  /// Adds a voxel a ray crosses (free unless it is, or becomes, an endpoint).
  void addFree(uint64_t code) { insert(code, false); }
  /// Adds an endpoint voxel (occupied).
  void addOccupied(uint64_t code) { insert(code, true); }
  /// Number of distinct voxels.
  std::size_t size() const { return used_.size(); }
  /// The entries as (code << 1 | occupied), sorted by code.
  const std::vector<uint64_t>& sorted();
  void clear();

private:
  inline void insert(uint64_t code, bool occupied);
  void grow();

  static constexpr uint64_t kEmpty = ~uint64_t(0);
  std::vector<uint64_t> slots_;  // (code << 1 | occupied) or kEmpty
  std::vector<uint32_t> used_;   // indices of the filled slots
  std::vector<uint64_t> sorted_, scratch_;
  uint64_t mask_;
  int shift_;
};

inline void KeySet::insert(uint64_t code, bool occupied) {
  const uint64_t entry = (code << 1) | (occupied ? 1u : 0u);
  // Low Morton bits first: voxels near each other (a ray's consecutive voxels) land in nearby slots, so the
  // walk stays in cache; the high bits are folded in to separate distant blocks.
  uint64_t i = (code ^ (code >> (64 - shift_)) ^ (code >> 2 * (64 - shift_))) & mask_;
  for (;;) {
    uint64_t& slot = slots_[i];
    if (slot == kEmpty) {
      slot = entry;
      used_.push_back(static_cast<uint32_t>(i));
      if (used_.size() * 2 > slots_.size())
        grow();
      return;
    }
    if ((slot >> 1) == code) {
      slot |= entry & 1u;  // occupied wins
      return;
    }
    i = (i + 1) & mask_;
  }
}

}  // namespace mapping
}  // namespace unexmin

#include <unexmin/mapping/key_set.h>

#include <algorithm>

namespace unexmin {
namespace mapping {

namespace {

/// The 16 bits of v spread to every third bit of 48.
uint64_t spread(uint64_t v) {
  v &= 0xFFFF;
  v = (v | (v << 16)) & 0x0000FF0000FFull;
  v = (v | (v << 8)) & 0x00F00F00F00Full;
  v = (v | (v << 4)) & 0x0C30C30C30C3ull;
  v = (v | (v << 2)) & 0x249249249249ull;
  return v;
}

constexpr int kInitialBits = 16;

}  // namespace

namespace {

struct SpreadTable {
  uint64_t byte[256];
  SpreadTable() {
    for (unsigned v = 0; v < 256; ++v)
      byte[v] = spread(v);
  }
};
const SpreadTable kSpread;

}  // namespace

uint64_t spreadBits(uint16_t v) {
  return kSpread.byte[v & 0xFF] | (kSpread.byte[v >> 8] << 24);
}

KeySet::KeySet()
    : slots_(std::size_t(1) << kInitialBits, kEmpty),
      mask_((uint64_t(1) << kInitialBits) - 1),
      shift_(64 - kInitialBits) {}

void KeySet::grow() {
  std::vector<uint64_t> entries;
  entries.reserve(used_.size());
  for (uint32_t i : used_)
    entries.push_back(slots_[i]);
  const int bits = 64 - shift_ + 1;
  slots_.assign(std::size_t(1) << bits, kEmpty);
  mask_ = (uint64_t(1) << bits) - 1;
  shift_ = 64 - bits;
  used_.clear();
  for (uint64_t e : entries)
    insert(e >> 1, e & 1u);
}

const std::vector<uint64_t>& KeySet::sorted() {
  sorted_.clear();
  sorted_.reserve(used_.size());
  for (uint32_t i : used_)
    sorted_.push_back(slots_[i]);
  // LSD radix sort of the 49-bit entries, 11 bits a pass (5 passes; std::sort below a few hundred entries).
  if (sorted_.size() < 256) {
    std::sort(sorted_.begin(), sorted_.end());
    return sorted_;
  }
  constexpr unsigned kBits = 11, kBuckets = 1u << kBits;
  scratch_.resize(sorted_.size());
  std::vector<uint64_t>* from = &sorted_;
  std::vector<uint64_t>* to = &scratch_;
  for (unsigned shift = 0; shift < 49; shift += kBits) {
    std::size_t count[kBuckets + 1] = {};
    for (uint64_t e : *from)
      ++count[((e >> shift) & (kBuckets - 1)) + 1];
    for (unsigned b = 0; b < kBuckets; ++b)
      count[b + 1] += count[b];
    for (uint64_t e : *from)
      (*to)[count[(e >> shift) & (kBuckets - 1)]++] = e;
    std::swap(from, to);
  }
  if (from != &sorted_)
    sorted_.swap(scratch_);
  return sorted_;
}

void KeySet::clear() {
  for (uint32_t i : used_)
    slots_[i] = kEmpty;
  used_.clear();
}

}  // namespace mapping
}  // namespace unexmin

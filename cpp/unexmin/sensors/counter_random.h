// A counter-based random stream (docs/sonars.md "Receiver"): SplitMix64 (Steele, Lea and Flood 2014) read at any
// position. Draw n (n = 0, 1, ...) of the stream with key K is
//   bits(n) = mix(K + (n + 1) gamma),   gamma = 0x9e3779b97f4a7c15 (2^64 / golden ratio, odd),
// mix = Stafford's "variant 13" 64-bit finaliser, SplitMix64's output function (it passes BigCrush). A draw depends on
// its key and index only, not on the draws read before it: work split over bins, beams or threads, or read out of
// order, sees the same numbers, and a loop of independent draws runs without a chain through a state. Seeded: the key
// comes from the sensor's seeded stream (random.h). Knows no ROS.
#pragma once

#include <cstdint>

namespace unexmin {
namespace sensors {

class CounterRandom {
public:
  static constexpr std::uint64_t kGamma = 0x9e3779b97f4a7c15ull;

  explicit CounterRandom(std::uint64_t key = 0) : key_(key) {}

  std::uint64_t key() const { return key_; }
  /// Draw n: 64 uniform random bits.
  std::uint64_t bits(std::uint64_t n) const { return mix(key_ + (n + 1) * kGamma); }
  /// Sub-stream `index` (e.g. one beam of a ping): the stream keyed by draw `index` of this one.
  CounterRandom stream(std::uint64_t index) const { return CounterRandom(bits(index)); }

  /// Stafford's variant 13 finaliser: a bijection of 64-bit words with full avalanche.
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

private:
  std::uint64_t key_;
};

}  // namespace sensors
}  // namespace unexmin

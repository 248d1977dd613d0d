// The random source of one sensor: a 64-bit Mersenne twister and its standard normal
// distribution, seeded from the world seed, the robot and the sensor name so that every run with
// the same seed repeats exactly and two sensors never share a stream.
#pragma once

#include <cstdint>
#include <random>
#include <string>

namespace unexmin {
namespace sensors {

class Random {
public:
  /// Seed of the stream of `sensor` on `robot` in a world seeded with `world_seed`
  /// (splitmix64 of the world seed mixed with the FNV-1a hash of "robot/sensor": stable across
  /// platforms and runs, unlike std::hash).
  static std::uint64_t streamSeed(std::uint64_t world_seed, const std::string& robot, const std::string& sensor) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a offset basis
    for (char c : robot + "/" + sensor) {
      h ^= static_cast<unsigned char>(c);
      h *= 1099511628211ull;  // FNV prime
    }
    std::uint64_t z = world_seed + 0x9e3779b97f4a7c15ull * (h | 1ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }

  void seed(std::uint64_t s) {
    engine_.seed(s);
    normal_.reset();
  }
  /// A standard normal draw.
  double gauss() { return normal_(engine_); }
  /// A uniform draw in [0, 1).
  double uniform() { return std::generate_canonical<double, 53>(engine_); }
  /// 64 uniform random bits (one step of the engine).
  std::uint64_t bits() { return engine_(); }

private:
  std::mt19937_64 engine_;
  std::normal_distribution<double> normal_;
};

}  // namespace sensors
}  // namespace unexmin

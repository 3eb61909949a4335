// counter-based random streams: a value depends only on (seed, stream, counter), so results
// never depend on thread count or evaluation order. SplitMix64-style mixing (Steele et al. 2014)
// applied to a Weyl sequence per stream; passes BigCrush as a 64-bit hash of the counter.
#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>

namespace gs {

constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// a stream of 64-bit values keyed by (seed, stream id); `counter` is its whole state
struct RngStream {
  std::uint64_t key = 0;      ///< derived from seed and stream id
  std::uint64_t counter = 0;  ///< how many values were drawn

  RngStream() = default;
  RngStream(std::uint64_t seed, std::uint64_t stream)
      : key(mix64(seed * 0x9e3779b97f4a7c15ULL + mix64(stream + 0x632be59bd9b4e019ULL))) {}

  std::uint64_t next_u64() { return mix64(key + 0x9e3779b97f4a7c15ULL * ++counter); }
  /// uniform in (0, 1): never exactly 0, so log() is safe
  double uniform() { return (static_cast<double>(next_u64() >> 11) + 0.5) * 0x1.0p-53; }
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// a pair of independent standard normals (Box–Muller, T.2.16)
  void normal_pair(double& z0, double& z1) {
    const double r = std::sqrt(-2.0 * std::log(uniform()));
    const double a = 2.0 * std::numbers::pi * uniform();
    z0 = r * std::cos(a);
    z1 = r * std::sin(a);
  }
  double normal() {
    double a, b;
    normal_pair(a, b);
    return a;
  }
};

}  // namespace gs

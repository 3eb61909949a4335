// counter-based random streams: a value depends only on (seed, stream, counter), so results
// never depend on thread count or evaluation order. SplitMix64-style mixing (Steele et al. 2014)
// applied to a Weyl sequence per stream; passes BigCrush as a 64-bit hash of the counter.
#pragma once
#include <cmath>
#include <cstdint>
#include <numbers>

namespace gs {

/// tables of the ziggurat normal sampler (Marsaglia & Tsang 2000, 128 layers)
struct ZigguratTables {
  std::uint32_t kn[128];
  double wn[128], fn[128];
  ZigguratTables() {
    const double m1 = 2147483648.0;  // 2^31
    double dn = 3.442619855899, tn = dn;
    const double vn = 9.91256303526217e-3;
    const double q = vn / std::exp(-0.5 * dn * dn);
    kn[0] = static_cast<std::uint32_t>((dn / q) * m1);
    kn[1] = 0;
    wn[0] = q / m1;
    wn[127] = dn / m1;
    fn[0] = 1.0;
    fn[127] = std::exp(-0.5 * dn * dn);
    for (int i = 126; i >= 1; --i) {
      dn = std::sqrt(-2.0 * std::log(vn / dn + std::exp(-0.5 * dn * dn)));
      kn[i + 1] = static_cast<std::uint32_t>((dn / tn) * m1);
      tn = dn;
      fn[i] = std::exp(-0.5 * dn * dn);
      wn[i] = dn / m1;
    }
  }
  static const ZigguratTables& get() {
    static const ZigguratTables t;
    return t;
  }
};

constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// the ziggurat's first try on the 64-bit value u, without a branch (normal_fast's common
/// case): the candidate normal x, accepted where this returns true (97.2% of values). Where it
/// returns false, normal_fast from the state that drew u gives the normal (it tries u again,
/// then draws on). The layer index is the low 7 bits, the signed abscissa the high 32.
inline bool ziggurat_try(const ZigguratTables& t, std::uint64_t u, double& x) {
  const auto hz = static_cast<std::int32_t>(static_cast<std::uint32_t>(u >> 32));
  const auto iz = static_cast<unsigned>(u & 127u);
  const auto ahz = static_cast<std::uint32_t>(hz < 0 ? -static_cast<std::int64_t>(hz) : hz);
  x = hz * t.wn[iz];
  return ahz < t.kn[iz];
}

/// a stream of 64-bit values keyed by (seed, stream id); `counter` is its whole state
struct RngStream {
  std::uint64_t key = 0;      ///< derived from seed and stream id
  std::uint64_t counter = 0;  ///< how many values were drawn

  RngStream() = default;
  RngStream(std::uint64_t seed, std::uint64_t stream)
      : key(mix64(seed * 0x9e3779b97f4a7c15ULL + mix64(stream + 0x632be59bd9b4e019ULL))) {}

  std::uint64_t next_u64() { return value(key, ++counter); }
  /// the value a stream keyed `key` draws as its `count`-th (counting from 1)
  static constexpr std::uint64_t value(std::uint64_t key, std::uint64_t count) {
    return mix64(key + 0x9e3779b97f4a7c15ULL * count);
  }
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
  /// a standard normal by the ziggurat method: exact, and ~10× cheaper than Box–Muller because
  /// 97.2% of draws need one 64-bit value and no transcendental function. The layer index (low
  /// 7 bits) and the signed 32-bit abscissa (high bits) come from disjoint bits of each value.
  double normal_fast() { return normal_fast(ZigguratTables::get()); }
  /// the same with the tables at hand (hot loops fetch them once)
  double normal_fast(const ZigguratTables& t) {
    for (;;) {
      const std::uint64_t u = next_u64();
      double x;
      if (ziggurat_try(t, u, x)) return x;  // inside the layer's rectangle
      const auto hz = static_cast<std::int32_t>(static_cast<std::uint32_t>(u >> 32));
      const int iz = static_cast<int>(u & 127u);
      if (iz == 0) {  // the tail beyond r (Marsaglia's method)
        constexpr double r = 3.442619855899;
        double xt, yt;
        do {
          xt = -std::log(uniform()) / r;
          yt = -std::log(uniform());
        } while (yt + yt < xt * xt);
        return hz > 0 ? r + xt : -r - xt;
      }
      // the wedge between layers: accept under the density
      if (t.fn[iz] + uniform() * (t.fn[iz - 1] - t.fn[iz]) < std::exp(-0.5 * x * x)) return x;
    }
  }
};

}  // namespace gs

// the random force's normals drawn a block at a time (noise_normals_block: the common ziggurat
// draws of every particle first, the rejected ones again in full) are those of noise_normals,
// bit for bit: the block form only reorders work, so no run's noise changes with it
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "core/rng.hpp"
#include "drive/random_force.hpp"

namespace gs {
namespace {

TEST(Noise, BlockDrawsAreThoseOfOneParticleAtATime) {
  const ZigguratTables& t = ZigguratTables::get();
  const std::vector<std::uint64_t> keys = random_force_keys(20261126, 6400);
  int redrawn = 0, tails = 0, checked = 0;
  for (const bool ring : {true, false}) {
    for (const std::int64_t step : {0, 1, 977, 1234567}) {
      for (const std::size_t m : {std::size_t{64}, std::size_t{37}, std::size_t{1}}) {
        for (std::size_t k = 0; k + m <= keys.size(); k += m) {
          double z0[64], z1[64];
          noise_normals_block(t, keys.data() + k, step, ring, m, z0, z1);
          for (std::size_t q = 0; q < m; ++q) {
            double a, b;
            noise_normals(t, keys[k + q], step, ring, a, b);
            ASSERT_EQ(std::bit_cast<std::uint64_t>(z0[q]), std::bit_cast<std::uint64_t>(a))
                << "ring " << ring << ", step " << step << ", particle " << k + q;
            if (!ring) {
              ASSERT_EQ(std::bit_cast<std::uint64_t>(z1[q]), std::bit_cast<std::uint64_t>(b));
            }
            ++checked;
            // how often the full draw was needed (the first try on the first or second value
            // rejected), and how often in the tail beyond the last layer
            const std::uint64_t c = static_cast<std::uint64_t>(step) << 8;
            double x;
            const std::uint64_t u0 = RngStream::value(keys[k + q], c + 1);
            const bool first = ziggurat_try(t, u0, x);
            const bool second = ring || ziggurat_try(t, RngStream::value(keys[k + q], c + 2), x);
            redrawn += !(first && second);
            tails += !first && (u0 & 127u) == 0;
          }
        }
      }
    }
  }
  // the rejected path was exercised: the first try fails for 2.8% of values (below), so for
  // ~2.8% of the ring's particles and ~5.4% of the plane's; the tail for ~1/128 of those
  EXPECT_GT(redrawn, checked / 100);
  EXPECT_LT(redrawn, checked / 10);
  EXPECT_GT(tails, 0);
}

TEST(Noise, ZigguratFirstTryIsNormalFastsFirstValue) {
  // where the first try accepts, normal_fast returns that value having drawn one value; where
  // it rejects, normal_fast draws more
  const ZigguratTables& t = ZigguratTables::get();
  int accepted = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    RngStream r(7, static_cast<std::uint64_t>(k));
    const std::uint64_t u = RngStream::value(r.key, 1);
    double x;
    const bool ok = ziggurat_try(t, u, x);
    const double z = r.normal_fast(t);
    if (ok) {
      ++accepted;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(z), std::bit_cast<std::uint64_t>(x));
      ASSERT_EQ(r.counter, 1u);
    } else {
      ASSERT_GT(r.counter, 1u);
    }
  }
  // the first try accepts where |hz| < kn[iz], |hz| uniform on [0, 2³¹] and iz on 0…127: with
  // probability mean(kn)/2³¹ = 0.9724 for these tables (5σ of the binomial count: 0.0019)
  double p = 0.0;
  for (const std::uint32_t kn : t.kn) p += kn / 2147483648.0 / 128.0;
  EXPECT_NEAR(p, 0.9724, 0.0001);
  EXPECT_NEAR(static_cast<double>(accepted) / n, p, 0.0019);
}

}  // namespace
}  // namespace gs

// geometry kernels of the polygon DEM hot loop: decagon–decagon overlap (in contact and the
// separated pairs a broad phase hands over), and decagon ∩ rectangle area for φ
// (docs/physics.md §2.1, §2.5)
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "geometry/polygon.hpp"
#include "geometry/prepared.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRBig = 9e-3;       // the paper's big decagon, m
constexpr double kRSmall = 6.36e-3;  // the paper's small decagon, m
constexpr int kPairs = 1024;

struct Pair {
  gs::Poly a, b;
};

// big–small decagon pairs at random orientations and directions, centre distance drawn in
// [lo, hi] × (sum of circumradii)
std::vector<Pair> make_pairs(double lo, double hi, std::uint64_t seed) {
  gs::RngStream rng(seed, 0);
  std::vector<Pair> pairs(kPairs);
  for (Pair& p : pairs) {
    const double ang = rng.uniform(0.0, 2.0 * kPi);
    const double dist = (kRBig + kRSmall) * rng.uniform(lo, hi);
    const gs::Vec2 ca{0.24, 0.3}, cb = ca + gs::Vec2{std::cos(ang), std::sin(ang)} * dist;
    p.a = gs::regular_polygon(10, kRBig, ca, rng.uniform(0.0, 2.0 * kPi));
    p.b = gs::regular_polygon(10, kRSmall, cb, rng.uniform(0.0, 2.0 * kPi));
  }
  return pairs;
}

// in contact: at 0.93–0.95 of the circumradius sum every pair overlaps (the apothem sum is
// cos 18° = 0.951 of it), a few per cent of the radius deep, as in a settled pile
void BM_DecagonOverlap(benchmark::State& state) {
  const std::vector<Pair> pairs = make_pairs(0.93, 0.95, 1);
  std::size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(gs::overlap(p.a, p.b));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecagonOverlap);

// just apart (centre distance 1.001–1.05 of the circumradius sum), as the near misses a
// broad phase with fattened boxes hands over: the reject path
void BM_DecagonSeparated(benchmark::State& state) {
  const std::vector<Pair> pairs = make_pairs(1.001, 1.05, 2);
  std::size_t i = 0;
  for (auto _ : state) {
    const Pair& p = pairs[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(gs::overlap(p.a, p.b));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecagonSeparated);

// the same pairs prepared once (as the force loop does per step): overlap(PolyRef, PolyRef)
gs::PolyStore prepare(const std::vector<Pair>& pairs) {
  gs::PolyStore st;
  st.resize(2 * pairs.size(), 10);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    st.set(2 * i, pairs[i].a);
    st.set(2 * i + 1, pairs[i].b);
  }
  return st;
}

// big–small pairs pressed together along the line of centres by a depth δ drawn log-uniformly
// in [lo, hi] × the small radius from where they first touch (found by bisection): the resting
// pile's overlaps (δ/r ≈ 10⁻³…10⁻²) and deeper ones
std::vector<Pair> make_pressed(double lo, double hi, std::uint64_t seed) {
  gs::RngStream rng(seed, 0);
  std::vector<Pair> pairs(kPairs);
  const gs::Vec2 ca{0.24, 0.3};
  for (Pair& p : pairs) {
    const double ang = rng.uniform(0.0, 2.0 * kPi);
    const gs::Vec2 u{std::cos(ang), std::sin(ang)};
    const double ta = rng.uniform(0.0, 2.0 * kPi), tb = rng.uniform(0.0, 2.0 * kPi);
    auto at = [&](double d) { return gs::regular_polygon(10, kRSmall, ca + u * d, tb); };
    p.a = gs::regular_polygon(10, kRBig, ca, ta);
    double in = 0.5 * (kRBig + kRSmall), out = kRBig + kRSmall;  // overlapping, apart
    for (int k = 0; k < 80; ++k) {
      const double mid = 0.5 * (in + out);
      (gs::overlap(p.a, at(mid)).area > 0.0 ? in : out) = mid;
    }
    p.b = at(out - kRSmall * std::exp(rng.uniform(std::log(lo), std::log(hi))));
  }
  return pairs;
}

// the prepared overlap on pressed pairs: arg 0 resting (δ/r 10⁻³…10⁻², a settled pile's
// overlaps), 1 deep (δ/r 0.02…0.3)
void BM_DecagonOverlapPressed(benchmark::State& state) {
  const gs::PolyStore st =
      prepare(state.range(0) == 0 ? make_pressed(1e-3, 1e-2, 6) : make_pressed(0.02, 0.3, 7));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPairs - 1);
    benchmark::DoNotOptimize(gs::overlap(st.ref(2 * k), st.ref(2 * k + 1)));
  }
  state.SetLabel(state.range(0) == 0 ? "resting" : "deep");
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecagonOverlapPressed)->Arg(0)->Arg(1);

void BM_DecagonOverlapPrepared(benchmark::State& state) {
  const gs::PolyStore st = prepare(make_pairs(0.93, 0.95, 1));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPairs - 1);
    benchmark::DoNotOptimize(gs::overlap(st.ref(2 * k), st.ref(2 * k + 1)));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecagonOverlapPrepared);

void BM_DecagonSeparatedPrepared(benchmark::State& state) {
  const gs::PolyStore st = prepare(make_pairs(1.001, 1.05, 2));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & (kPairs - 1);
    benchmark::DoNotOptimize(gs::overlap(st.ref(2 * k), st.ref(2 * k + 1)));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_DecagonSeparatedPrepared);

// the per-step preparation of the pile's 1184 decagons (world-frame vertices, edges, vertex
// mean, bounding circle), as the force loop runs it before the pairs: time per decagon
void BM_DecagonPrepare(benchmark::State& state) {
  constexpr int kCount = 1184;
  gs::RngStream rng(5, 0);
  const gs::Poly big = gs::regular_polygon(10, kRBig), small = gs::regular_polygon(10, kRSmall);
  std::vector<gs::Vec2> c(kCount);
  std::vector<double> th(kCount);
  for (int i = 0; i < kCount; ++i) {
    c[i] = {rng.uniform(0.0, 0.48), rng.uniform(0.0, 1.2)};
    th[i] = rng.uniform(-20.0, 20.0);
  }
  const gs::BodyExtent eb = gs::body_extent(big), es = gs::body_extent(small);
  gs::PolyStore st;
  st.resize(kCount, 10);
  for (auto _ : state) {
    for (int i = 0; i < kCount; ++i)
      st.set_placed(i, (i & 1) ? small : big, (i & 1) ? es : eb, c[i], th[i]);
    benchmark::DoNotOptimize(st.ref(kCount - 1).radius);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kCount);
}
BENCHMARK(BM_DecagonPrepare);

// decagons scattered over a region twice the test rectangle: inside, outside and straddling
void BM_AreaInRect(benchmark::State& state) {
  gs::RngStream rng(3, 0);
  std::vector<gs::Poly> polys(kPairs);
  for (gs::Poly& p : polys)
    p = gs::regular_polygon(10, kRBig, {rng.uniform(0.0, 0.48), rng.uniform(0.0, 0.48)},
                            rng.uniform(0.0, 2.0 * kPi));
  std::size_t i = 0;
  for (auto _ : state) {
    const gs::Poly& p = polys[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(gs::area_in_rect(p, 0.04, 0.04, 0.44, 0.44));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AreaInRect);

// every decagon straddles a rectangle side (the clipping path)
void BM_AreaInRectStraddling(benchmark::State& state) {
  gs::RngStream rng(4, 0);
  std::vector<gs::Poly> polys(kPairs);
  for (gs::Poly& p : polys)
    p = gs::regular_polygon(10, kRBig, {0.04 + rng.uniform(-kRBig, kRBig), rng.uniform(0.1, 0.4)},
                            rng.uniform(0.0, 2.0 * kPi));
  std::size_t i = 0;
  for (auto _ : state) {
    const gs::Poly& p = polys[i++ & (kPairs - 1)];
    benchmark::DoNotOptimize(gs::area_in_rect(p, 0.04, 0.04, 0.44, 0.44));
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_AreaInRectStraddling);

}  // namespace

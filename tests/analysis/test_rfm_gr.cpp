// pair correlation g(R) (T.4.10)
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "analysis/rfm_gr.hpp"
#include "core/error.hpp"
#include "core/rng.hpp"

namespace gs::rfm {
namespace {

std::vector<Vec2> random_points(RngStream& rng, int n, double box) {
  std::vector<Vec2> p(static_cast<std::size_t>(n));
  for (Vec2& q : p) q = {rng.uniform(0.0, box), rng.uniform(0.0, box)};
  return p;
}

TEST(RfmPairCorrelation, IdealGasIsOne) {
  // iid uniform points on a torus: pair separations are pairwise independent, so a bin count
  // is binomial with mean M·p ≈ Poisson; g_err = g/√pairs is its σ. 4.5σ per bin over 40 bins.
  RngStream rng(21, 0);
  const double box = 2.0;
  PairCorrelation2D gr(box, 0.5 * box, 40);
  for (int s = 0; s < 30; ++s) gr.add_snapshot(random_points(rng, 300, box));
  double chi2 = 0.0;
  for (const GrBin& b : gr.bins()) {
    ASSERT_GT(b.pairs, 100.0);
    EXPECT_NEAR(b.g, 1.0, 4.5 / std::sqrt(b.pairs)) << "R = " << b.r;
    chi2 += std::pow((b.g - 1.0) * std::sqrt(b.pairs), 2);
  }
  // the bins together: χ² with 40 dof, mean 40, σ ≈ 9; reject beyond +5σ
  EXPECT_LT(chi2, 40.0 + 5.0 * std::sqrt(80.0));
}

TEST(RfmPairCorrelation, CellListAgreesWithBruteForce) {
  // R_max = L/4 takes the cell list, R_max = L/2 the brute-force loop; with equal bin widths the
  // first bins must hold the same pairs (a pair exactly on a bin edge may round either way)
  RngStream rng(22, 0);
  const auto pts = random_points(rng, 500, 1.0);
  PairCorrelation2D cells(1.0, 0.25, 20), brute(1.0, 0.5, 40);
  cells.add_snapshot(pts);
  brute.add_snapshot(pts);
  const auto a = cells.bins(), b = brute.bins();
  double ta = 0, tb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].pairs, b[i].pairs, 1.0) << i;
    ta += a[i].pairs;
    tb += b[i].pairs;
  }
  EXPECT_NEAR(ta, tb, 1.0);
  EXPECT_GT(ta, 1000.0);
}

TEST(RfmPairCorrelation, SquareLatticeCoordinationShells) {
  // m×m lattice of spacing a: each point has 4 neighbours at a, 4 at √2 a, 4 at 2a; the
  // cumulative coordination ρ Σ g·(annulus area) with ρ = (N−1)/L² must count them exactly
  const int m = 20;
  const double box = 1.0, a = box / m;
  std::vector<Vec2> pts;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) pts.push_back({(i + 0.5) * a, (j + 0.5) * a});
  PairCorrelation2D gr(box, 0.5, 97);  // 97 bins keep a, √2a, 2a off the bin edges
  gr.add_snapshot(pts);
  const double rho = (m * m - 1.0) / (box * box);
  auto coordination = [&](double r) {
    double c = 0.0;
    for (const GrBin& b : gr.bins())
      if (b.r_hi <= r) c += rho * b.g * std::numbers::pi * (b.r_hi * b.r_hi - b.r_lo * b.r_lo);
    return c;
  };
  EXPECT_NEAR(coordination(1.2 * a), 4.0, 1e-9);
  EXPECT_NEAR(coordination(1.6 * a), 8.0, 1e-9);
  EXPECT_NEAR(coordination(2.1 * a), 12.0, 1e-9);
  EXPECT_NEAR(coordination(0.9 * a), 0.0, 1e-12);
}

TEST(RfmPairCorrelation, RejectsRangesBeyondHalfTheBox) {
  EXPECT_THROW(PairCorrelation2D(1.0, 0.6, 10), InputError);
  EXPECT_THROW(PairCorrelation2D(1.0, 0.4, 0), InputError);
}

}  // namespace
}  // namespace gs::rfm

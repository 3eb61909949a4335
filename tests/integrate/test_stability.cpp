// stability limits on a damped oscillator q'' = −ω²q − 2ζωq' (the linearised contact):
// the largest ω·Δt each scheme survives, against the known limits of the explicit schemes
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "integrate/integrator.hpp"

namespace gs {
namespace {

double stable_limit(IntegratorKind kind, double zeta) {
  double last = 0;
  for (double wdt = 0.01; wdt < 3.0; wdt += 0.01) {
    auto in = make_integrator(kind);
    std::vector<double> q{1}, v{0}, a{-1};
    std::vector<Channel> c{{q, v, a}};
    in->init(c, wdt);
    bool ok = true;
    for (int s = 0; s < 5000 && ok; ++s) {
      in->predict(c, wdt, ThreadTeam{});
      a[0] = -q[0] - 2 * zeta * v[0];
      in->correct(c, wdt, ThreadTeam{});
      ok = 0.5 * (v[0] * v[0] + q[0] * q[0]) < 1.5;
    }
    if (!ok) break;
    last = wdt;
  }
  return last;
}

TEST(IntegratorStability, LimitsOfTheExplicitSchemes) {
  // Verlet: the textbook limit ω·Δt < 2 without damping (grid step 0.01)
  EXPECT_NEAR(stable_limit(IntegratorKind::VelocityVerlet, 0.0), 2.0, 0.011);
  EXPECT_NEAR(stable_limit(IntegratorKind::PositionVerlet, 0.0), 2.0, 0.011);
  const double gear0 = stable_limit(IntegratorKind::Gear6, 0.0);
  const double gear25 = stable_limit(IntegratorKind::Gear6, 0.25);
  std::printf(
      "[ measured ] Gear6 stable to w*dt = %.2f (zeta 0), %.2f (zeta 0.25); "
      "VV %.2f (zeta 0.25); SIE %.2f (zeta 0.25)\n",
      gear0, gear25, stable_limit(IntegratorKind::VelocityVerlet, 0.25),
      stable_limit(IntegratorKind::SemiImplicitEuler, 0.25));
  // the Gear predictor–corrector pays for its accuracy with a far smaller stability region
  EXPECT_LT(gear0, 1.0);
  EXPECT_LT(gear25, gear0);
}

}  // namespace
}  // namespace gs

// Haff's law for a dilute freely cooling disk gas (T.1.2), derived for 2D disks:
// with T = ⟨|v|²⟩ (T.2.19), dT/dt = −A·T^{3/2}, so T^{−1/2} grows linearly with slope
// A/2 = n·χ·σ·(1 − ε²)·√(π/8), n = N/L², σ = 2r, χ = (1 − 7φ/16)/(1 − φ)² = 1/s*(φ) (Henderson;
// the thesis's s*). The thesis's (1.2) is this with T per degree of freedom and 1 − ε² ≈ 2(1 − ε).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "force/laws/disk_law.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

double temperature(const World& w) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    mx += w.s.vx[i];
    my += w.s.vy[i];
  }
  mx /= w.size();
  my /= w.size();
  double t = 0;
  for (std::size_t i = 0; i < w.size(); ++i)
    t += (w.s.vx[i] - mx) * (w.s.vx[i] - mx) + (w.s.vy[i] - my) * (w.s.vy[i] - my);
  return t / w.size();
}

TEST(HaffsLaw, DiluteDiskGasCoolsAtThePredictedRate) {
  const int n = 1000;
  const double phi = 0.1, eps = 0.9;
  SceneSpec s = build::disk_gas(n, phi, eps, 1.0, 11);
  s.prep.velocity_amplitude = std::sqrt(24.0);  // ⟨|v|²⟩ = a²/6 = 4 m²/s²
  const double m12 = 3.53e-5 / 2;
  s.integrator.dt = law::contact_time(5e5, m12, law::gamma_normal(eps, m12, 5e5)) / 20;
  testing::TestWorld tw(s);
  Simulation& sim = tw.start();
  const World& w = sim.world();
  const double L = s.box.width, sigma = 3e-3;
  const double chi = (1 - 7 * phi / 16) / ((1 - phi) * (1 - phi));
  const double slope = (n / (L * L)) * chi * sigma * (1 - eps * eps) * std::sqrt(M_PI / 8);

  // let the uniform initial velocities relax to the cooling state (a few collisions each)
  sim.run(static_cast<std::int64_t>(0.015 / s.integrator.dt));
  // then sample T^{−1/2}(t) until T has dropped about threefold, and fit a line
  std::vector<double> ts, ys;
  const std::int64_t every = static_cast<std::int64_t>(0.002 / s.integrator.dt);
  const double t_end = w.s.t + 0.07;
  while (w.s.t < t_end) {
    ts.push_back(w.s.t);
    ys.push_back(1 / std::sqrt(temperature(w)));
    sim.run(every);
  }
  double mt = 0, my = 0;
  for (std::size_t k = 0; k < ts.size(); ++k) {
    mt += ts[k];
    my += ys[k];
  }
  mt /= ts.size();
  my /= ts.size();
  double sxy = 0, sxx = 0;
  for (std::size_t k = 0; k < ts.size(); ++k) {
    sxy += (ts[k] - mt) * (ys[k] - my);
    sxx += (ts[k] - mt) * (ts[k] - mt);
  }
  const double measured = sxy / sxx;
  std::printf(
      "[ measured ] Haff slope of T^-1/2: %.4f, predicted %.4f (ratio %.3f); T fell %.2fx\n",
      measured, slope, measured / slope, std::pow(ys.back() / ys.front(), 2));
  // Enskog theory neglects velocity correlations and the non-Gaussian cooling state (a few %);
  // 1000 grains give ~3% noise in T: 10% is a test that still fails for a wrong (1 − ε) or χ
  EXPECT_NEAR(measured / slope, 1.0, 0.10);
}

}  // namespace
}  // namespace gs

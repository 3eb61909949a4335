// the random force (docs/physics.md §4, T.2.16, T.2.18) on free particles: each component of the
// velocity diffuses with 2D/M² per unit time, so in 2D d⟨|v|²⟩/dt = 4D/M², the same at any Δt
// (docs/physics.md §7). In 1D the kicks are symmetrised every step: the total momentum stays
// exactly what it was and ⟨v²⟩ grows at 2D/M²·(1 − 1/N).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

constexpr double kD = 1e-8, kM = 3.53e-5;

// N thesis beads spread over a box so large that none meets another in the test time
std::string free_scene(const char* box, int n, double dt, int com_every) {
  return std::string(R"(
[model]
kind = "S"
rotation = false
[[species]]
name = "bead"
radius = 0.0015
mass = 3.53e-5
count = )") +
         std::to_string(n) + "\n[box]\n" + box + R"(
[preparation]
placement = "uniform"
seed = 5
[integrator]
dt = )" + std::to_string(dt) +
         R"(
[drive]
kind = "random_force"
D = 1e-8
com_removal_every = )" +
         std::to_string(com_every) + "\n";
}

struct Heating {
  double mean = 0.0;  ///< ⟨|v|²⟩ (2D) or ⟨v_x²⟩ (1D), m²/s²
  double se = 0.0;    ///< its standard error over particles, m²/s²
  double px = 0.0;    ///< total momentum x, kg m/s
  long contacts = 0;  ///< contacts seen (should stay 0)
};

Heating heat(const std::string& text, double t) {
  SceneSpec s = parse_scene_string(text, "noise.toml");
  World w = make_world(s);
  place_particles(w, s);
  Simulation sim(std::move(w), SimSettings::from(s));
  Heating h;
  const auto steps = static_cast<std::int64_t>(std::llround(t / s.integrator.dt));
  for (std::int64_t k = 0; k < steps; ++k) {
    sim.step();
    h.contacts += static_cast<long>(sim.contacts().keys.size());
  }
  const World& wr = sim.world();
  const double n = static_cast<double>(wr.size());
  double s1 = 0, s2 = 0;
  for (std::size_t i = 0; i < wr.size(); ++i) {
    const double v2 = wr.s.vx[i] * wr.s.vx[i] + wr.s.vy[i] * wr.s.vy[i];
    s1 += v2;
    s2 += v2 * v2;
    h.px += wr.mass[i] * wr.s.vx[i];
  }
  h.mean = s1 / n;
  h.se = std::sqrt((s2 / n - h.mean * h.mean) / (n - 1));
  return h;
}

// 2D: ⟨|v|²⟩(t) = (4D/M²)(t − Δt/2) for velocity Verlet (the last kick counts half); at
// t = 0.01 s the Δt/2 is ≤ 0.05 %. The tolerance is 4 standard errors of the particle mean
// (|v|² is exponentially distributed, so se ≈ ⟨|v|²⟩/√N ≈ 1.4 % for N = 5000).
TEST(RfmNoise, FreeParticlesHeatAt4DOverM2IndependentOfDt) {
  const double t = 0.01, rate = 4.0 * kD / (kM * kM);  // 32.1 m²/s³
  for (double dt : {1e-6, 1e-5}) {
    const Heating h = heat(free_scene("kind = \"periodic\"\nwidth = 10.0", 5000, dt, 0), t);
    EXPECT_EQ(h.contacts, 0);
    const double expect = rate * (t - dt / 2);
    EXPECT_NEAR(h.mean, expect, 4.0 * h.se) << "dt = " << dt;
    EXPECT_LT(h.se / expect, 0.02);
    std::printf("2D free heating dt = %g s: <|v|^2>/(4D/M^2 t) = %.4f +- %.4f\n", dt,
                h.mean / expect, h.se / expect);
  }
}

// 1D ring: the symmetrised kicks (T.2.18) sum to zero, so the total momentum of particles
// started at rest stays zero to round-off, and each one heats at 2D/M²·(1 − 1/N)
TEST(RfmNoise, RingKicksAreSymmetrised) {
  const int n = 4000;
  const double t = 0.01, dt = 1e-5;
  const Heating h = heat(free_scene("kind = \"ring\"\nwidth = 400.0", n, dt, 0), t);
  EXPECT_EQ(h.contacts, 0);
  const double v_scale = std::sqrt(2.0 * kD / (kM * kM) * t);  // ~0.57 m/s
  EXPECT_LT(std::abs(h.px), 1e-12 * n * kM * v_scale);
  const double expect = 2.0 * kD / (kM * kM) * (t - dt / 2) * (1.0 - 1.0 / n);
  EXPECT_NEAR(h.mean, expect, 4.0 * h.se);
}

}  // namespace
}  // namespace gs

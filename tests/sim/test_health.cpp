// run-time health checks: a deliberately too-large Δt is caught with a diagnosis, never
// written out as NaN; the up-front advice flags it too
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "force/laws/disk_law.hpp"
#include "sim/stability.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

TEST(Health, TooLargeStepIsCaughtWithADiagnosis) {
  SceneSpec s = build::disk_gas(400, 0.4, 0.9, 1.0, 5);
  const double m12 = 3.53e-5 / 2;
  const double tc = law::contact_time(5e5, m12, law::gamma_normal(0.9, m12, 5e5));
  s.integrator.dt = 0.9 * tc;  // ω·Δt ≈ 2.8: far beyond velocity Verlet's limit (≈ 2)
  s.health.check_every = 10;
  s.health.max_overlap = 10.0;  // let the energy check be the one to fire
  testing::TestWorld tw(s);
  Simulation& sim = tw.start();
  const StepAdvice a = time_step_advice(sim);
  EXPECT_FALSE(a.stable);
  EXPECT_NE(a.message.find("use dt <="), std::string::npos);
  EXPECT_LT(a.suggested_dt, tc / 2);
  try {
    sim.run(200000);
    FAIL() << "the blow-up went unnoticed";
  } catch (const HealthError& e) {
    const std::string m = e.what();
    EXPECT_TRUE(m.find("mechanical energy grew") != std::string::npos ||
                m.find("non-finite") != std::string::npos)
        << m;
    EXPECT_NE(m.find("try dt <="), std::string::npos) << m;
    EXPECT_NE(m.find("particle"), std::string::npos) << m;
  }
}

TEST(Health, ReferenceSettingsAreStable) {
  // the thesis disks at Δt = 1e-6 s and the paper grains at 5e-5 s (Gear 6) pass the advice
  testing::TestWorld disks(build::disk_gas(100, 0.3, 0.6, 0.6, 1));
  EXPECT_TRUE(time_step_advice(disks.start()).stable);
  testing::TestWorld pile(build::decagon_pile(50, 0.1, 0.5, 1));
  const StepAdvice a = time_step_advice(pile.start());
  EXPECT_TRUE(a.stable) << a.message;
  std::printf("[ measured ] paper grains, Gear 6, dt 5e-5: omega*dt = %.3f (limit %.2f)\n",
              a.omega_dt, a.limit);
}

// two disks of different stiffness, pressed together and let go side by side: an elastic pair
// conserves energy, so the check must stay quiet in either order of the two, and its yardstick
// holds the spring the law uses — the pair's mean stiffness, not either disk's own
TEST(Health, TwoMaterialPairUsesTheLawsStiffness) {
  const double r = 0.001, m = 1e-5, delta = 0.02 * r;
  const MaterialSpec soft = build::disk_material(1.0, 1.0, 1e3);
  MaterialSpec stiff = build::disk_material(1.0, 1.0, 1e5);
  stiff.name = "stiff";
  const double k_pair = 0.5 * (soft.ks + stiff.ks);
  const double tc = law::contact_time(k_pair, 0.5 * m, 0.0);
  for (const bool soft_first : {true, false}) {
    SceneSpec s = build::two_body(ModelKind::Disk, ShapeKind::Disk, r, m, 0, soft,
                                  IntegratorKind::VelocityVerlet, tc / 200);
    s.materials.push_back(stiff);
    SpeciesSpec b = s.species[0];
    b.name = "b";
    b.material = "stiff";
    s.species.push_back(b);
    s.health.check_every = 1;
    // both move along the line of the contact's tangent, so the start has kinetic energy of
    // the size of the spring's (the check's slack is 5 % of it)
    const double e_spring = 0.5 * k_pair * delta * delta;
    const double v = std::sqrt(e_spring / m);
    const std::string first = soft_first ? "a" : "b", second = soft_first ? "b" : "a";
    s.prep.particles.push_back({first, 0.0, 0.0, 0.0, v, 0.0, 0.0});
    s.prep.particles.push_back({second, 0.0, 2 * r - delta, 0.0, v, 0.0, 0.0});
    testing::TestWorld tw(s);
    Simulation& sim = tw.start();
    const double kinetic = 2 * 0.5 * m * v * v;
    EXPECT_NEAR(sim.energy_yardstick().first, kinetic + e_spring, 1e-12 * e_spring)
        << (soft_first ? "soft first" : "stiff first");
    EXPECT_NO_THROW(sim.run(2000)) << (soft_first ? "soft first" : "stiff first");
    // the pair has parted: its spring's energy is now motion along the normal
    EXPECT_GT(tw.x(1).y - tw.x(0).y, 2 * r);
  }
}

}  // namespace
}  // namespace gs

// thesis Table 2.1 two-disk collisions (M = 1 kg) under Model S, every integrator:
// realised normal restitution, lost fraction of centre-of-mass kinetic energy, momentum
#include <gtest/gtest.h>

#include <cmath>

#include "force/laws/disk_law.hpp"
#include "test_world.hpp"

namespace gs {
namespace {

using testing::TestWorld;

constexpr double kR = 0.5;   // radius: Table 2.1's unit spacing is one diameter
constexpr double kM = 1.0;   // kg (Table 2.1)
constexpr double kKs = 5e5;  // N/m (thesis fig. 2.5b)

// relative kinetic energy in the centre-of-mass frame of two equal masses
double cm_energy(Vec2 v1, Vec2 v2) { return 0.25 * kM * norm2(v1 - v2); }

struct Case {
  IntegratorKind integ;
  double eps;
};

class DiskCollision : public ::testing::TestWithParam<Case> {};

// simulation 1 of Table 2.1: head-on, x2 = (1,0), v1 = (1,0)
TEST_P(DiskCollision, HeadOnRealisesTargetRestitution) {
  const auto [integ, eps] = GetParam();
  const double m12 = kM / 2;
  const double tc = law::contact_time(kKs, m12, law::gamma_normal(eps, m12, kKs));
  TestWorld tw(build::two_body(ModelKind::Disk, ShapeKind::Disk, kR, kM, 0,
                               build::disk_material(eps, 1.0, kKs), integ, tc / 200));
  // start just apart so the flight is short: gap 1e-3 along x
  tw.particle(0.0, 0.0, 1.0, 0.0).particle(2 * kR + 1e-3, 0.0, 0.0, 0.0);
  tw.start();
  const Vec2 p0 = tw.momentum();
  const double e0 = cm_energy(tw.v(0), tw.v(1));
  ASSERT_TRUE(tw.run_through_collision(1000000));
  const double realised = -(tw.v(0).x - tw.v(1).x) / 1.0;
  // T.2.6 makes the linear dashpot's restitution exact; what remains is the integrator's
  // resolution of a contact sampled 200 times: 1% is the acceptance
  EXPECT_NEAR(realised, eps, 0.01 * eps) << to_string(integ);
  // lost fraction of CM kinetic energy 1 − ε² (T.2.13, docs/physics.md §8.7)
  const double lost = 1.0 - cm_energy(tw.v(0), tw.v(1)) / e0;
  EXPECT_NEAR(lost, 1.0 - eps * eps, 0.02 * eps * eps);
  // momentum: forces are equal and opposite, so only round-off remains. Position Verlet
  // carries velocity as a position difference over Δt, whose round-off is ~ε·|x|/Δt
  const double tol =
      integ == IntegratorKind::PositionVerlet ? 8 * 2.2e-16 * (2 * kR + 1e-3) / (tc / 200) : 1e-12;
  EXPECT_NEAR(tw.momentum().x, p0.x, tol);
  EXPECT_NEAR(tw.momentum().y, p0.y, tol);
}

INSTANTIATE_TEST_SUITE_P(
    AllIntegrators, DiskCollision,
    ::testing::Values(
        Case{IntegratorKind::VelocityVerlet, 0.1}, Case{IntegratorKind::VelocityVerlet, 0.3},
        Case{IntegratorKind::VelocityVerlet, 0.5}, Case{IntegratorKind::VelocityVerlet, 0.7},
        Case{IntegratorKind::VelocityVerlet, 0.9}, Case{IntegratorKind::VelocityVerlet, 0.99},
        Case{IntegratorKind::Gear6, 0.1}, Case{IntegratorKind::Gear6, 0.5},
        Case{IntegratorKind::Gear6, 0.9}, Case{IntegratorKind::Gear6, 0.99},
        Case{IntegratorKind::PositionVerlet, 0.1}, Case{IntegratorKind::PositionVerlet, 0.5},
        Case{IntegratorKind::PositionVerlet, 0.99}, Case{IntegratorKind::SemiImplicitEuler, 0.1},
        Case{IntegratorKind::SemiImplicitEuler, 0.5},
        Case{IntegratorKind::SemiImplicitEuler, 0.99}),
    [](const auto& info) {
      return std::string(to_string(info.param.integ)) + "_eps" +
             std::to_string(static_cast<int>(std::lround(info.param.eps * 100)));
    });

// simulations 2–4 of Table 2.1: the energy lost is 1 − ε_n² cos²θ − ε_t,eff² sin²θ with
// ε_t,eff = ε_t^√(1+(ln ε_n/π)²) (docs/physics.md §3) and θ the angle between relative velocity
// and normal
struct Oblique {
  Vec2 x2, v1;
};
class ObliqueCollision : public ::testing::TestWithParam<std::tuple<int, double>> {};

TEST_P(ObliqueCollision, LosesPredictedEnergyFraction) {
  const Oblique table[3] = {{{1, 1}, {1, 1}}, {{kR, 1}, {0, 1}}, {{1, 1}, {1 + kR, 1}}};
  const auto [sim, eps] = GetParam();
  const Oblique c = table[sim - 2];
  const double m12 = kM / 2;
  const double tc = law::contact_time(kKs, m12, law::gamma_normal(eps, m12, kKs));
  TestWorld tw(build::two_body(ModelKind::Disk, ShapeKind::Disk, kR, kM, 0,
                               build::disk_material(eps, eps, kKs), IntegratorKind::VelocityVerlet,
                               tc / 200));
  tw.particle(0, 0, c.v1.x, c.v1.y).particle(c.x2.x, c.x2.y, 0, 0);
  tw.start();
  const Vec2 p0 = tw.momentum();
  const double e0 = cm_energy(tw.v(0), tw.v(1));
  // the impact geometry: normal at contact from the straight-line approach
  const Vec2 u = normalized(c.v1);
  const double b = std::abs(cross(c.x2, u));  // impact parameter
  const double sin_t = b / (2 * kR), cos2 = 1 - sin_t * sin_t;
  ASSERT_TRUE(tw.run_through_collision(5000000));
  const double a = std::log(eps) / M_PI;
  const double et_eff = std::pow(eps, std::sqrt(1 + a * a));
  const double predicted = 1 - eps * eps * cos2 - et_eff * et_eff * sin_t * sin_t;
  const double lost = 1 - cm_energy(tw.v(0), tw.v(1)) / e0;
  // the normal turns by ~δ/r ≈ 1e-3 rad during the contact, so 1% of the fraction suffices
  EXPECT_NEAR(lost, predicted, 0.01) << "simulation " << sim << " eps " << eps;
  EXPECT_NEAR(norm(tw.momentum() - p0), 0.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Table21, ObliqueCollision,
                         ::testing::Combine(::testing::Values(2, 3, 4),
                                            ::testing::Values(0.1, 0.5, 0.9)));

}  // namespace
}  // namespace gs

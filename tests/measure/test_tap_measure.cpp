// the per-tap measurements (docs/physics.md §2.5) on hand-built packings with exact answers: φ of
// the test rectangle and its halves, segregation counts n(h), and the force-moment tensor (P.41) of
// a decagon resting on the floor
#include <gtest/gtest.h>

#include <cmath>

#include "measure/tap_measure.hpp"
#include "sim/simulation.hpp"

namespace gs {
namespace {

SceneSpec two_species_scene() {
  SceneSpec s;
  MaterialSpec m;
  m.name = "grain";
  s.materials.push_back(m);
  for (auto [name, r] : {std::pair{"big", 0.009}, std::pair{"small", 0.00636}}) {
    SpeciesSpec sp;
    sp.name = name;
    sp.radius = r;
    sp.count = 1;
    s.species.push_back(sp);
  }
  s.box.width = 0.4;
  s.box.height = 0.4;
  return s;
}

// regular decagon area (docs/physics.md §1.1): (n/2) r² sin(2π/n)
double decagon_area(double r) { return 5.0 * r * r * std::sin(2.0 * M_PI / 10.0); }

// a decagon with θ = 0 is mirror-symmetric about the horizontal and vertical lines through its
// centre: centred on an edge of the rectangle exactly half of it is inside, on a corner a quarter
World hand_packing() {
  World w = make_world(two_species_scene());
  w.add_particle(0, {0.20, 0.15}, 0.0);  // big, inside, on the line between the halves
  w.add_particle(1, {0.15, 0.15}, 0.0);  // small, inside the left half
  w.add_particle(0, {0.10, 0.15}, 0.0);  // big, on the left edge: half
  w.add_particle(1, {0.25, 0.20}, 0.0);  // small, on the top edge (right half): half
  w.add_particle(0, {0.30, 0.10}, 0.0);  // big, on the lower right corner: a quarter
  w.add_particle(1, {0.35, 0.35}, 0.0);  // small, outside
  w.add_particle(1, {0.27, 0.13}, 0.3);  // small, rotated, inside the right half
  return w;
}

TEST(TapMeasure, PhiOfAHandBuiltPackingIsExact) {
  const World w = hand_packing();
  const double Ab = decagon_area(0.009), As = decagon_area(0.00636);
  const double rect[4] = {0.1, 0.1, 0.3, 0.2};
  const TapMeasurement m = measure_tap(w, ContactSet{}, rect);
  // whole: 1 + ½ + ¼ big, 1 + ½ + 1 small, over 0.2 × 0.1 m²
  const double phi = (1.75 * Ab + 2.5 * As) / 0.02;
  // left [0.1, 0.2]: ½ + ½ big, 1 small; right [0.2, 0.3]: ½ + ¼ big, ½ + 1 small; 0.01 m² each
  const double left = (1.0 * Ab + 1.0 * As) / 0.01, right = (0.75 * Ab + 1.5 * As) / 0.01;
  EXPECT_NEAR(m.phi, phi, 1e-12 * phi);
  EXPECT_NEAR(m.phi_left, left, 1e-12 * left);
  EXPECT_NEAR(m.phi_right, right, 1e-12 * right);
  // equal halves: their mean is the whole
  EXPECT_NEAR(0.5 * (m.phi_left + m.phi_right), m.phi, 1e-13);
  // heights: all grains and per species
  EXPECT_NEAR(m.z_mean, (0.15 + 0.15 + 0.15 + 0.20 + 0.10 + 0.35 + 0.13) / 7, 1e-15);
  ASSERT_EQ(m.z_species.size(), 2u);
  EXPECT_NEAR(m.z_species[0], (0.15 + 0.15 + 0.10) / 3, 1e-15);
  EXPECT_NEAR(m.z_species[1], (0.15 + 0.20 + 0.35 + 0.13) / 4, 1e-15);
  // nothing moves, nothing touches
  EXPECT_EQ(m.kinetic_energy, 0.0);
  EXPECT_EQ(m.max_speed, 0.0);
  EXPECT_EQ(m.coordination, 0.0);
}

// n(h) counts centres strictly below h on the fixed grid h = 0.1, 0.2, 0.3, 0.4 m
TEST(TapMeasure, SegregationCountsOnTheHeightGrid) {
  const World w = hand_packing();
  const std::vector<double> grid = height_grid(0.4, 0.1);
  ASSERT_EQ(grid.size(), 4u);
  EXPECT_DOUBLE_EQ(grid.back(), 0.4);
  const std::vector<double> n = cumulative_counts(w, grid);
  // big at y = 0.15, 0.15, 0.10; small at 0.15, 0.20, 0.35, 0.13
  const std::vector<double> expect{0, 3, 3, 3, 0, 2, 3, 4};
  EXPECT_EQ(n, expect);
  const auto names = cumulative_count_names(w, grid);
  ASSERT_EQ(names.size(), 8u);
  EXPECT_EQ(names[0], "big@100");
  EXPECT_EQ(names[7], "small@400");
}

// a decagon resting face-down on the floor: the floor pushes up with m·g at the middle of the
// contact line, which lies on the floor's face y = 0, so the force moment (P.41) is
// S_yy = (s − x)_y·F_y = −m·g·y_centre and the other components vanish
TEST(TapMeasure, ForceMomentOfAGrainRestingOnTheFloor) {
  SceneSpec s = two_species_scene();
  s.species.resize(1);
  s.box.width = 0.1;
  s.integrator.kind = IntegratorKind::VelocityVerlet;
  s.integrator.dt = 5e-5;
  World w = make_world(s);
  const double r = 0.009, apothem = r * std::cos(M_PI / 10);
  w.add_particle(0, {0.05, apothem + 1e-4}, 0.0);  // θ = 0: a face is horizontal at the bottom
  Simulation sim(std::move(w), SimSettings::from(s));
  sim.run(10000);  // 0.5 s: it lands and comes to rest
  const World& v = sim.world();
  const double rect[4] = {0.0, 0.0, 0.1, 0.1};
  const TapMeasurement m = measure_tap(v, sim.contacts(), rect);
  const double mg = v.mass[0] * 9.81, y = v.s.y[0];
  std::printf(
      "[ measured ] resting decagon: y = %.6f m (apothem %.6f), S = [%.3e %.3e; %.3e %.3e] N m,"
      " -m g y = %.6e, KE %.1e J\n",
      y, apothem, m.S[0], m.S[1], m.S[2], m.S[3], -mg * y, m.kinetic_energy);
  ASSERT_LT(m.max_speed, 1e-6);  // at rest
  // the overlap sinks the grain a little into the floor (a few µm)
  EXPECT_LT(y, apothem);
  EXPECT_GT(y, apothem - 1e-4);
  EXPECT_NEAR(m.S[3], -mg * y, 1e-5 * mg * y);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(m.S[k], 0.0, 1e-5 * mg * y) << "component " << k;
  EXPECT_EQ(m.coordination, 0.0);  // wall contacts are not counted
}

}  // namespace
}  // namespace gs

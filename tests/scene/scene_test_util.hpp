// shared helpers for the scene tests: a full scene that sets every key to a non-default
// value, a line finder, an error catcher and a field-by-field comparison of two specs
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "scene/parse.hpp"

namespace gs::test {

/// every key set, every value different from its default (so a dropped key shows up)
inline const char* kFullScene = R"(# a full polygon scene
[scene]
name = "pile"
description = "bidisperse \"decagons\"\nsecond line"
duration = 2.5

[model]
kind = "polygon_dem"
hdot_finite_difference = true
clip_attractive = true
rotation = false

[[material]]
name = "steel"
E = 2000
gamma = 0.25
mu = 0.3
ks = 1e5
eps_n = 0.9
eps_t = 0.8

[[material]]
name = "wall"
E = 3000.0
gamma = 0.0
mu = 0.0
ks = 2.5e5
eps_n = 1.0
eps_t = 0.5

[[species]]
name = "big"
shape = "polygon"
sides = 10
radius = 0.009
count = 544
density = 2.0
material = "steel"

[[species]]
name = "small"
sides = 7
radius = 0.00636
count = 640
mass = 0.002
material = "wall"

[box]
kind = "walls"
width = 0.48
height = 0.9
lid = true
wall_thickness = 0.04
material = "wall"

[preparation]
placement = "hexagonal"
seed = 42
column_height = 1.2
velocity_amplitude = 0.1
settle_time = 0.5

[integrator]
kind = "semi_implicit_euler"
dt = 1e-5
broad_phase = "cell_grid"

[drive]
kind = "rotating_g"
g = 9.8
gx = 0.5
gy = -0.5
g_p = 20
t1 = 0.2
period = 4.0
f = 0.75
relax = 2.0
D = 2e-8
com_removal_every = 50
early_rest = true
rest_speed = 2e-3
rest_energy = 3e-6
rest_hold = 0.2
quench = true
quench_speed = 0.04
quench_hold = 0.08
taps = 300

[health]
max_overlap = 0.1
check_every = 10
allow_unstable = true

[output]
series_every = 7
final_state = false
test_rect = [0.05, 0.06, 0.43, 0.44]
discard_taps = 20
)";

/// 1-based line of the first occurrence of `needle` in `text` (computed from the text itself)
inline int line_of(std::string_view text, std::string_view needle) {
  auto pos = text.find(needle);
  EXPECT_NE(pos, std::string_view::npos) << "test bug: '" << needle << "' not in scene";
  int line = 1;
  for (std::size_t i = 0; i < pos; ++i) line += text[i] == '\n';
  return line;
}

/// the InputError message of parsing `text` (fails the test if nothing is thrown)
inline std::string error_of(std::string_view text, const std::vector<std::string>& ov = {},
                            const std::string& name = "scenes/t.toml") {
  try {
    parse_scene_string(text, name, ov);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return {};
}

/// replace the first occurrence of `from` by `to` (the edit must apply)
inline std::string edit(std::string text, std::string_view from, std::string_view to) {
  auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << "test bug: '" << from << "' not found";
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

/// every field of two specs equal, except path, line numbers and resolved
inline void expect_same(const SceneSpec& a, const SceneSpec& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.duration, b.duration);
  EXPECT_EQ(a.model.kind, b.model.kind);
  EXPECT_EQ(a.model.hdot_finite_difference, b.model.hdot_finite_difference);
  EXPECT_EQ(a.model.clip_attractive, b.model.clip_attractive);
  EXPECT_EQ(a.model.rotation, b.model.rotation);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (std::size_t i = 0; i < a.materials.size(); ++i) {
    const auto &x = a.materials[i], &y = b.materials[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.E, y.E);
    EXPECT_EQ(x.gamma, y.gamma);
    EXPECT_EQ(x.mu, y.mu);
    EXPECT_EQ(x.ks, y.ks);
    EXPECT_EQ(x.eps_n, y.eps_n);
    EXPECT_EQ(x.eps_t, y.eps_t);
  }
  ASSERT_EQ(a.species.size(), b.species.size());
  for (std::size_t i = 0; i < a.species.size(); ++i) {
    const auto &x = a.species[i], &y = b.species[i];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.shape, y.shape);
    EXPECT_EQ(x.sides, y.sides);
    EXPECT_EQ(x.radius, y.radius);
    EXPECT_EQ(x.count, y.count);
    EXPECT_EQ(x.density, y.density);
    EXPECT_EQ(x.mass, y.mass);
    EXPECT_EQ(x.material, y.material);
  }
  EXPECT_EQ(a.box.kind, b.box.kind);
  EXPECT_EQ(a.box.width, b.box.width);
  EXPECT_EQ(a.box.height, b.box.height);
  EXPECT_EQ(a.box.lid, b.box.lid);
  EXPECT_EQ(a.box.wall_thickness, b.box.wall_thickness);
  EXPECT_EQ(a.box.reduced_length, b.box.reduced_length);
  EXPECT_EQ(a.box.material, b.box.material);
  EXPECT_EQ(a.prep.placement, b.prep.placement);
  EXPECT_EQ(a.prep.seed, b.prep.seed);
  EXPECT_EQ(a.prep.column_height, b.prep.column_height);
  EXPECT_EQ(a.prep.velocity_amplitude, b.prep.velocity_amplitude);
  EXPECT_EQ(a.prep.settle_time, b.prep.settle_time);
  ASSERT_EQ(a.prep.particles.size(), b.prep.particles.size());
  for (std::size_t i = 0; i < a.prep.particles.size(); ++i) {
    const auto &x = a.prep.particles[i], &y = b.prep.particles[i];
    EXPECT_EQ(x.species, y.species);
    EXPECT_EQ(x.x, y.x);
    EXPECT_EQ(x.y, y.y);
    EXPECT_EQ(x.theta, y.theta);
    EXPECT_EQ(x.vx, y.vx);
    EXPECT_EQ(x.vy, y.vy);
    EXPECT_EQ(x.omega, y.omega);
  }
  EXPECT_EQ(a.integrator.kind, b.integrator.kind);
  EXPECT_EQ(a.integrator.dt, b.integrator.dt);
  EXPECT_EQ(a.integrator.broad_phase, b.integrator.broad_phase);
  const auto &d = a.drive, &e = b.drive;
  EXPECT_EQ(d.kind, e.kind);
  EXPECT_EQ(d.g, e.g);
  EXPECT_EQ(d.gx, e.gx);
  EXPECT_EQ(d.gy, e.gy);
  EXPECT_EQ(d.g_p, e.g_p);
  EXPECT_EQ(d.t1, e.t1);
  EXPECT_EQ(d.period, e.period);
  EXPECT_EQ(d.f, e.f);
  EXPECT_EQ(d.relax, e.relax);
  EXPECT_EQ(d.D, e.D);
  EXPECT_EQ(d.com_removal_every, e.com_removal_every);
  EXPECT_EQ(d.early_rest, e.early_rest);
  EXPECT_EQ(d.rest_speed, e.rest_speed);
  EXPECT_EQ(d.rest_energy, e.rest_energy);
  EXPECT_EQ(d.rest_hold, e.rest_hold);
  EXPECT_EQ(d.quench, e.quench);
  EXPECT_EQ(d.quench_speed, e.quench_speed);
  EXPECT_EQ(d.quench_hold, e.quench_hold);
  EXPECT_EQ(d.taps, e.taps);
  EXPECT_EQ(a.health.max_overlap, b.health.max_overlap);
  EXPECT_EQ(a.health.check_every, b.health.check_every);
  EXPECT_EQ(a.health.allow_unstable, b.health.allow_unstable);
  EXPECT_EQ(a.output.series_every, b.output.series_every);
  EXPECT_EQ(a.output.final_state, b.output.final_state);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(a.output.test_rect[i], b.output.test_rect[i]);
  EXPECT_EQ(a.output.discard_taps, b.output.discard_taps);
}

}  // namespace gs::test

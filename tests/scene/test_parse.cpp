// scene parsing: a full scene reads back every value as written, defaults fill the rest,
// overrides take effect, scene_to_toml round-trips, and every shipped scene parses
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "scene/names.hpp"
#include "scene/scene_test_util.hpp"

namespace gs {
namespace {

using test::edit;
using test::kFullScene;

// the full scene: each value as written in kFullScene (exact: these are decimal literals,
// and the parser must hand back the nearest double, which == on the same literal checks)
TEST(SceneParse, FullSceneGivesTheWrittenValues) {
  SceneSpec s = parse_scene_string(kFullScene, "scenes/full.toml");
  EXPECT_EQ(s.path, "scenes/full.toml");
  EXPECT_EQ(s.name, "pile");
  EXPECT_EQ(s.description, "bidisperse \"decagons\"\nsecond line");
  EXPECT_EQ(s.duration, 2.5);
  EXPECT_EQ(s.model.kind, ModelKind::Polygon);  // via the alias "polygon_dem"
  EXPECT_TRUE(s.model.hdot_finite_difference);
  EXPECT_TRUE(s.model.clip_attractive);
  EXPECT_FALSE(s.model.rotation);

  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_EQ(s.materials[0].name, "steel");
  EXPECT_EQ(s.materials[0].E, 2000.0);  // integer accepted for a float
  EXPECT_EQ(s.materials[0].gamma, 0.25);
  EXPECT_EQ(s.materials[0].mu, 0.3);
  EXPECT_EQ(s.materials[0].ks, 1e5);
  EXPECT_EQ(s.materials[0].eps_n, 0.9);
  EXPECT_EQ(s.materials[0].eps_t, 0.8);
  EXPECT_EQ(s.materials[0].line, test::line_of(kFullScene, "[[material]]"));
  EXPECT_EQ(s.materials[1].eps_n, 1.0);  // the closed end of (0, 1]
  EXPECT_EQ(s.materials[1].gamma, 0.0);

  ASSERT_EQ(s.species.size(), 2u);
  const SpeciesSpec& big = s.species[0];
  EXPECT_EQ(big.name, "big");
  EXPECT_EQ(big.shape, ShapeKind::Polygon);
  EXPECT_EQ(big.sides, 10);
  EXPECT_EQ(big.radius, 0.009);
  EXPECT_EQ(big.count, 544);
  EXPECT_EQ(big.density, 2.0);
  EXPECT_FALSE(big.mass.has_value());
  EXPECT_EQ(big.material, "steel");
  EXPECT_EQ(big.line, test::line_of(kFullScene, "[[species]]"));
  const SpeciesSpec& small = s.species[1];
  EXPECT_EQ(small.sides, 7);
  EXPECT_EQ(small.radius, 0.00636);
  EXPECT_EQ(small.count, 640);
  ASSERT_TRUE(small.mass.has_value());
  EXPECT_EQ(*small.mass, 0.002);
  EXPECT_EQ(small.material, "wall");

  EXPECT_EQ(s.box.kind, BoxKind::Walls);
  EXPECT_EQ(s.box.width, 0.48);
  EXPECT_EQ(s.box.height, 0.9);
  EXPECT_TRUE(s.box.lid);
  EXPECT_EQ(s.box.wall_thickness, 0.04);
  EXPECT_EQ(s.box.material, "wall");
  EXPECT_FALSE(s.box.reduced_length.has_value());

  EXPECT_EQ(s.prep.placement, PlacementKind::Hexagonal);
  EXPECT_EQ(s.prep.seed, 42u);
  EXPECT_EQ(s.prep.column_height, 1.2);
  EXPECT_EQ(s.prep.velocity_amplitude, 0.1);
  EXPECT_EQ(s.prep.settle_time, 0.5);
  EXPECT_TRUE(s.prep.particles.empty());

  EXPECT_EQ(s.integrator.kind, IntegratorKind::SemiImplicitEuler);
  EXPECT_EQ(s.integrator.dt, 1e-5);
  EXPECT_EQ(s.integrator.broad_phase, BroadPhaseKind::CellGrid);

  EXPECT_EQ(s.drive.kind, DriveKind::RotatingG);
  EXPECT_EQ(s.drive.g, 9.8);
  EXPECT_EQ(s.drive.gx, 0.5);
  EXPECT_EQ(s.drive.gy, -0.5);
  EXPECT_EQ(s.drive.g_p, 20.0);
  EXPECT_EQ(s.drive.t1, 0.2);
  EXPECT_EQ(s.drive.period, 4.0);
  EXPECT_EQ(s.drive.f, 0.75);
  EXPECT_EQ(s.drive.relax, 2.0);
  EXPECT_EQ(s.drive.D, 2e-8);
  EXPECT_EQ(s.drive.com_removal_every, 50);
  EXPECT_TRUE(s.drive.early_rest);
  EXPECT_EQ(s.drive.rest_speed, 2e-3);
  EXPECT_EQ(s.drive.rest_energy, 3e-6);
  EXPECT_EQ(s.drive.rest_hold, 0.2);
  EXPECT_TRUE(s.drive.quench);
  EXPECT_EQ(s.drive.quench_speed, 0.04);
  EXPECT_EQ(s.drive.quench_hold, 0.08);
  EXPECT_EQ(s.drive.taps, 300);

  EXPECT_EQ(s.health.max_overlap, 0.1);
  EXPECT_EQ(s.health.check_every, 10);
  EXPECT_TRUE(s.health.allow_unstable);

  EXPECT_EQ(s.output.series_every, 7);
  EXPECT_FALSE(s.output.final_state);
  EXPECT_EQ(s.output.test_rect[0], 0.05);
  EXPECT_EQ(s.output.test_rect[1], 0.06);
  EXPECT_EQ(s.output.test_rect[2], 0.43);
  EXPECT_EQ(s.output.test_rect[3], 0.44);
  EXPECT_EQ(s.output.discard_taps, 20);
}

// resolved: every key of the file appears with its value in canonical TOML spelling
TEST(SceneParse, ResolvedListsEveryKey) {
  SceneSpec s = parse_scene_string(kFullScene, "full.toml");
  const auto& r = s.resolved;
  EXPECT_EQ(r.at("scene.name"), "\"pile\"");
  EXPECT_EQ(r.at("model.kind"), "\"P\"");  // alias written canonically
  EXPECT_EQ(r.at("material[0].E"), "2000.0");
  EXPECT_EQ(r.at("species[1].radius"), "0.00636");
  EXPECT_EQ(r.at("species[1].mass"), "0.002");
  EXPECT_EQ(r.at("species[1].shape"), "\"polygon\"");  // a default, resolved
  EXPECT_EQ(r.at("integrator.dt"), "1e-05");
  EXPECT_EQ(r.at("output.test_rect"), "[0.05, 0.06, 0.43, 0.44]");
  EXPECT_EQ(r.at("drive.taps"), "300");
  // 7 keys per material, 8 per species (with mass) / 7 (without), and the fixed sections:
  // scene 3, model 5, box 6, preparation 5, integrator 4, drive 19, health 3, output 7,
  // render 26
  EXPECT_EQ(r.size(), 3u + 5 + 2 * 7 + 7 + 8 + 6 + 5 + 4 + 19 + 3 + 7 + 26);
  EXPECT_EQ(r.at("integrator.sort_every"), "-1");
  EXPECT_EQ(r.at("drive.quench"), "true");
}

// defaults: a minimal Model P scene takes the documented defaults (spec.hpp, docs/physics.md §2)
TEST(SceneParse, DefaultsApply) {
  const char* text = R"(
[[species]]
name = "g"
radius = 0.009
count = 10

[box]
width = 0.48
)";
  SceneSpec s = parse_scene_string(text, "scenes/minimal.toml");
  EXPECT_EQ(s.name, "minimal");  // the file's stem
  EXPECT_EQ(s.duration, 1.0);
  EXPECT_EQ(s.model.kind, ModelKind::Polygon);
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  EXPECT_EQ(s.materials[0].E, 1000.0);  // paper parameters (docs/physics.md §2.2)
  EXPECT_EQ(s.materials[0].gamma, 0.5);
  EXPECT_EQ(s.materials[0].mu, 0.6);
  EXPECT_EQ(s.species[0].shape, ShapeKind::Polygon);
  EXPECT_EQ(s.species[0].sides, 10);
  EXPECT_EQ(s.species[0].density, 1.0);
  EXPECT_EQ(s.species[0].material, "default");
  EXPECT_EQ(s.box.kind, BoxKind::Walls);
  EXPECT_EQ(s.box.height, 1.0);
  EXPECT_FALSE(s.box.lid);
  EXPECT_EQ(s.box.material, "default");
  EXPECT_EQ(s.prep.placement, PlacementKind::LooseColumn);
  EXPECT_EQ(s.prep.seed, 1u);
  EXPECT_EQ(s.integrator.kind, IntegratorKind::Gear6);  // docs/physics.md §2.3
  EXPECT_EQ(s.integrator.dt, 5e-5);                     // docs/physics.md §2.2
  EXPECT_EQ(s.drive.kind, DriveKind::Gravity);
  EXPECT_EQ(s.drive.g, 9.81);
  EXPECT_EQ(s.drive.g_p, 6.0);
  EXPECT_EQ(s.drive.t1, 0.1);  // (P.37)
  EXPECT_EQ(s.drive.period, 3.0);
  EXPECT_FALSE(s.drive.early_rest);
  EXPECT_FALSE(s.drive.quench);  // opt-in (docs/tapping.md)
  EXPECT_EQ(s.drive.quench_speed, 0.05);
  EXPECT_EQ(s.drive.quench_hold, 0.3);
  EXPECT_EQ(s.output.discard_taps, 10);  // docs/physics.md §2.5
  EXPECT_EQ(s.output.test_rect[2], 0.44);
  EXPECT_EQ(s.resolved.at("integrator.kind"), "\"gear6\"");
  EXPECT_EQ(s.resolved.at("species[0].sides"), "10");
}

// Model S defaults (docs/physics.md §3): disks, velocity Verlet at 1e-6 s, square periodic box,
// no drive
TEST(SceneParse, SoftDiskDefaults) {
  const char* text = R"(
[model]
kind = "S"
[[species]]
name = "bead"
radius = 0.0015
mass = 3.53e-5
count = 2000
[box]
kind = "periodic"
width = 0.2
)";
  SceneSpec s = parse_scene_string(text, "rfm.toml");
  EXPECT_EQ(s.model.kind, ModelKind::Disk);
  EXPECT_EQ(s.species[0].shape, ShapeKind::Disk);
  EXPECT_EQ(s.integrator.kind, IntegratorKind::VelocityVerlet);
  EXPECT_EQ(s.integrator.dt, 1e-6);
  EXPECT_EQ(s.box.height, 0.2);
  EXPECT_EQ(s.drive.kind, DriveKind::None);
  EXPECT_EQ(s.prep.placement, PlacementKind::Random);
  EXPECT_FALSE(s.resolved.count("species[0].sides"));  // disks have no sides
}

// a ring given by L′: L = L′ + N·d (docs/physics.md §5.2); 1 + 100·0.003 = 1.3 up to one
// rounding each
TEST(SceneParse, RingLengthFromReducedLength) {
  const char* text = R"(
model.kind = "soft_disk"
[[species]]
name = "d"
radius = 0.0015
count = 100
[box]
kind = "ring"
reduced_length = 1.0
[drive]
kind = "random_force"
)";
  SceneSpec s = parse_scene_string(text, "ring.toml");
  EXPECT_EQ(s.box.kind, BoxKind::Ring1D);
  ASSERT_TRUE(s.box.reduced_length.has_value());
  EXPECT_NEAR(s.box.width, 1.3, 1e-12);
  EXPECT_EQ(s.drive.D, 1e-8);  // thesis noise strength
  // and it round-trips through L′ alone
  SceneSpec back = parse_scene_string(scene_to_toml(s), "ring2.toml");
  test::expect_same(s, back);
}

// explicit particles: counts follow from the list, species default to the only one
TEST(SceneParse, ExplicitParticles) {
  const char* text = R"(
[[species]]
name = "dec"
radius = 0.01
[box]
width = 1.0
[[preparation.particle]]
x = 0.3
y = 0.2
theta = 0.1
vx = 1
[[preparation.particle]]
species = "dec"
x = 0.7
y = 0.2
vx = -1
omega = 2.5
)";
  SceneSpec s = parse_scene_string(text, "two.toml");
  EXPECT_EQ(s.species[0].count, 2);
  ASSERT_EQ(s.prep.particles.size(), 2u);
  EXPECT_EQ(s.prep.particles[0].species, "dec");
  EXPECT_EQ(s.prep.particles[0].x, 0.3);
  EXPECT_EQ(s.prep.particles[0].theta, 0.1);
  EXPECT_EQ(s.prep.particles[0].vx, 1.0);
  EXPECT_EQ(s.prep.particles[1].vx, -1.0);
  EXPECT_EQ(s.prep.particles[1].omega, 2.5);
  EXPECT_EQ(s.prep.particles[1].vy, 0.0);
  EXPECT_EQ(s.resolved.at("preparation.particle[1].omega"), "2.5");
  test::expect_same(s, parse_scene_string(scene_to_toml(s), "back.toml"));
}

// overrides: numbers, bare words, quoted strings, arrays, new sections, indexed tables
TEST(SceneParse, OverridesTakeEffect) {
  SceneSpec s =
      parse_scene_string(kFullScene, "full.toml",
                         {"drive.g_p=8", "integrator.kind=velocity_verlet", "box.kind=\"periodic\"",
                          "species[1].count=5", "output.test_rect=[0, 0, 0.1, 0.2]",
                          "scene.name = my run", "model.rotation=true", "preparation.seed=7"});
  EXPECT_EQ(s.drive.g_p, 8.0);
  EXPECT_EQ(s.integrator.kind, IntegratorKind::VelocityVerlet);
  EXPECT_EQ(s.box.kind, BoxKind::Periodic);
  EXPECT_EQ(s.species[1].count, 5);
  EXPECT_EQ(s.output.test_rect[3], 0.2);
  EXPECT_EQ(s.name, "my run");
  EXPECT_TRUE(s.model.rotation);
  EXPECT_EQ(s.prep.seed, 7u);
  EXPECT_EQ(s.resolved.at("drive.g_p"), "8.0");
  // untouched keys keep their file values
  EXPECT_EQ(s.drive.t1, 0.2);
  // a section the file lacks is created; later overrides win
  const char* minimal = "[[species]]\nname='g'\nradius=0.01\ncount=1\n[box]\nwidth=1\n";
  SceneSpec m =
      parse_scene_string(minimal, "m.toml", {"health.check_every=7", "health.check_every=9"});
  EXPECT_EQ(m.health.check_every, 9);
}

// round trip: scene_to_toml(s) parses back to the same spec, and to the same resolved keys
TEST(SceneParse, RoundTrip) {
  SceneSpec s = parse_scene_string(kFullScene, "full.toml");
  std::string text = scene_to_toml(s);
  SceneSpec back = parse_scene_string(text, "back.toml");
  test::expect_same(s, back);
  EXPECT_EQ(s.resolved, back.resolved);
  // and the text is a fixed point
  EXPECT_EQ(scene_to_toml(back), text);
}

// round trip of a spec built in code (no file): awkward doubles survive exactly
TEST(SceneParse, RoundTripOfBuiltSpec) {
  SceneSpec s;
  s.name = "built";
  s.materials.emplace_back().name = "m";
  SpeciesSpec& sp = s.species.emplace_back();
  sp.name = "a";
  sp.radius = 0.1 + 0.2;
  sp.count = 3;
  s.integrator.dt = 1.0 / 3.0;
  s.drive.g = 9.81 * (1 + 1e-15);
  s.prep.seed = 9007199254740993ull;  // above 2^53: kept as an integer, not a double
  s.output.test_rect[0] = -1e-300;
  SceneSpec back = parse_scene_string(scene_to_toml(s), "built.toml");
  EXPECT_EQ(back.species[0].radius, 0.1 + 0.2);
  EXPECT_EQ(back.integrator.dt, 1.0 / 3.0);
  EXPECT_EQ(back.drive.g, s.drive.g);
  EXPECT_EQ(back.prep.seed, 9007199254740993ull);
  EXPECT_EQ(back.output.test_rect[0], -1e-300);
  EXPECT_EQ(back.species[0].material, "m");  // empty reference resolved to the first

  // explicit particles with count left at 0 (as builders do): the list sets the count
  s.species[0].count = 0;
  s.prep.particles.push_back({.species = "a", .x = 1.0, .y = 2.0});
  s.prep.particles.push_back({.species = "a", .x = 3.0, .y = 2.0});
  SceneSpec two = parse_scene_string(scene_to_toml(s), "two.toml");
  EXPECT_EQ(two.species[0].count, 2);
  EXPECT_EQ(two.prep.particles[1].x, 3.0);
}

// files: parse_scene_file reads from disk and names the path; a missing file is an error
TEST(SceneParse, FromFile) {
  auto dir = std::filesystem::path(testing::TempDir()) / "gs_scene_test";
  std::filesystem::create_directories(dir);
  auto path = (dir / "pile.toml").string();
  std::ofstream(path) << kFullScene;
  SceneSpec s = parse_scene_file(path, {"drive.f=2"});
  EXPECT_EQ(s.path, path);
  EXPECT_EQ(s.drive.f, 2.0);
  try {
    parse_scene_file((dir / "missing.toml").string());
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.toml"), std::string::npos) << e.what();
  }
}

// every scene shipped in scenes/ parses (scenes/studies/ holds study files, not scenes)
TEST(SceneParse, ShippedScenesParse) {
  std::filesystem::path dir = std::filesystem::path(GS_SOURCE_DIR) / "scenes";
  int n = 0;
  if (std::filesystem::exists(dir))
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() != ".toml") continue;
      ++n;
      EXPECT_NO_THROW({
        try {
          SceneSpec s = parse_scene_file(e.path().string());
          // and each one survives the round trip
          test::expect_same(s, parse_scene_string(scene_to_toml(s), "rt.toml"));
        } catch (const InputError& err) {
          ADD_FAILURE() << err.what();
          throw;
        }
      }) << e.path();
    }
  if (n == 0) GTEST_SKIP() << "no scenes under " << dir;
}

// enum tables: every canonical name reads back to its value
TEST(SceneNames, CanonicalNamesRoundTrip) {
  for (auto n : enum_names(DriveKind{}))
    EXPECT_EQ(scene_enum<DriveKind>(scene_name(n.value)), n.value);
  for (auto n : enum_names(IntegratorKind{}))
    EXPECT_EQ(scene_enum<IntegratorKind>(scene_name(n.value)), n.value);
  EXPECT_EQ(scene_name(ModelKind::Disk), "S");
  EXPECT_EQ(scene_enum<ModelKind>("soft_disk"), ModelKind::Disk);
  EXPECT_FALSE(scene_enum<ModelKind>("s").has_value());
}

}  // namespace
}  // namespace gs

namespace gs {
namespace {

// the ```toml examples of docs/scene-format.md, in order
std::vector<std::string> doc_examples() {
  std::ifstream in(std::string(GS_SOURCE_DIR) + "/docs/scene-format.md");
  std::vector<std::string> out;
  std::string line, block;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```toml") {
      inside = true;
      block.clear();
    } else if (inside && line == "```") {
      inside = false;
      out.push_back(block);
    } else if (inside) {
      block += line + "\n";
    }
  }
  return out;
}

// the documented examples parse and describe the published systems: the paper's grains cover
// 0.2056 m² (docs/physics.md §1.1: n/2·r²·sin(2π/n) per decagon), the thesis fluid has
// φ = Nπr²/L² = 0.353 (T.2.24), and the ring length is L′ + N·d; tolerances are the rounding of
// the quoted values
TEST(SceneDocs, ExamplesParseToThePublishedSystems) {
  auto ex = doc_examples();
  ASSERT_EQ(ex.size(), 3u) << "docs/scene-format.md should hold three ```toml examples";
  SceneSpec pile = parse_scene_string(ex[0], "docs/pile.toml");
  double area = 0;
  for (const auto& sp : pile.species)
    area += sp.count * sp.sides / 2.0 * sp.radius * sp.radius * std::sin(2 * M_PI / sp.sides);
  EXPECT_NEAR(area, 0.2056, 0.5e-4);
  EXPECT_EQ(pile.drive.kind, DriveKind::NegativeG);
  EXPECT_EQ(pile.species[0].count + pile.species[1].count, 1184);

  SceneSpec rfm = parse_scene_string(ex[1], "docs/rfm.toml");
  const auto& b = rfm.species[0];
  double phi = b.count * M_PI * b.radius * b.radius / (rfm.box.width * rfm.box.height);
  EXPECT_NEAR(phi, 0.353, 0.5e-3);
  EXPECT_EQ(rfm.drive.kind, DriveKind::RandomForce);
  EXPECT_EQ(rfm.materials[0].eps_n, 0.6);

  SceneSpec ring = parse_scene_string(ex[2], "docs/ring.toml");
  EXPECT_NEAR(ring.box.width, 4.0, 1e-12);
}

}  // namespace
}  // namespace gs

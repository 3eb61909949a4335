// the World → frame adapter: shapes, walls, box, colours, overlays, contact quantities, and the
// agreement of the [render] names with what the renderer knows
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/colormap.hpp"
#include "scene/parse.hpp"
#include "scene/render_section.hpp"
#include "sim/simulation.hpp"
#include "view/render_world.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

// three grains of two species (decagons and heptagons) at known positions and speeds in a
// 0.2 m × 0.3 m walled box without lid
const char* kScene = R"(
[[species]]
name = "big"
radius = 0.009
sides = 10

[[species]]
name = "hept"
radius = 0.006
sides = 7

[box]
width = 0.2
height = 0.3
wall_thickness = 0.02

[[preparation.particle]]
species = "big"
x = 0.05
y = 0.1
theta = 0.3
vx = 0.0

[[preparation.particle]]
species = "hept"
x = 0.1
y = 0.15
theta = -1.0
vx = 0.15
vy = 0.2

[[preparation.particle]]
species = "big"
x = 0.15
y = 0.2
vy = -1.0
omega = 2.0

[output]
test_rect = [0.02, 0.03, 0.18, 0.2]
)";

World world_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  const SceneSpec s = parse_scene_string(text, "t.toml", sets);
  World w = make_world(s);
  place_particles(w, s);
  return w;
}

// what the view takes of the same scene
ViewSettings view_of(const std::string& text, const std::vector<std::string>& sets = {}) {
  return ViewSettings::from(parse_scene_string(text, "t.toml", sets));
}

TEST(RenderWorld, ParticlesKeepTheirShapesOrientationsAndVelocities) {
  const World w = world_of(kScene);
  const RenderParticles p = world_particles(w);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p.x, (std::vector<double>{0.05, 0.1, 0.15}));
  EXPECT_EQ(p.y, (std::vector<double>{0.1, 0.15, 0.2}));
  EXPECT_EQ(p.theta, (std::vector<double>{0.3, -1.0, 0.0}));
  EXPECT_EQ(p.radius, (std::vector<double>{0.009, 0.006, 0.009}));
  EXPECT_EQ(p.sides, (std::vector<int>{10, 7, 10}));
  EXPECT_EQ(p.species, (std::vector<int>{0, 1, 0}));
  EXPECT_EQ(p.vx, (std::vector<double>{0.0, 0.15, 0.0}));
  EXPECT_EQ(p.vy, (std::vector<double>{0.0, 0.2, -1.0}));
  EXPECT_TRUE(p.value_extra.empty());
}

TEST(RenderWorld, WallsAndBox) {
  const World w = world_of(kScene);
  const RenderWalls walls = world_walls(w);
  // floor and two side walls (no lid), 0.02 m thick, up to the box height plus thickness
  ASSERT_EQ(walls.rects.size(), 3u);
  auto bounds = [](const std::array<Vec2, 4>& q) {
    std::array<double, 4> b{1e9, 1e9, -1e9, -1e9};
    for (const Vec2& c : q) {
      b[0] = std::min(b[0], c.x), b[1] = std::min(b[1], c.y);
      b[2] = std::max(b[2], c.x), b[3] = std::max(b[3], c.y);
    }
    return b;
  };
  const auto floor = bounds(walls.rects[0]), left = bounds(walls.rects[1]),
             right = bounds(walls.rects[2]);
  EXPECT_NEAR(floor[0], -0.02, 1e-15);
  EXPECT_NEAR(floor[1], -0.02, 1e-15);
  EXPECT_NEAR(floor[2], 0.22, 1e-15);
  EXPECT_NEAR(floor[3], 0.0, 1e-15);
  EXPECT_NEAR(left[2], 0.0, 1e-15);
  EXPECT_NEAR(left[3], 0.32, 1e-15);
  EXPECT_NEAR(right[0], 0.2, 1e-15);
  const BoxExtent b = world_box(w);
  EXPECT_EQ(b.x1, 0.2);
  EXPECT_EQ(b.y1, 0.3);
  EXPECT_FALSE(b.periodic_x || b.periodic_y);
  // a lid adds a fourth wall; a periodic box has none and wraps both ways
  EXPECT_EQ(world_walls(world_of(kScene, {"box.lid=true"})).rects.size(), 4u);
  const World per = world_of(kScene, {"box.kind=periodic"});
  EXPECT_TRUE(world_walls(per).rects.empty());
  EXPECT_TRUE(world_box(per).periodic_x && world_box(per).periodic_y);
}

TEST(RenderWorld, SpeedColoursRunFromRestToTheFastestGrain) {
  const World w = world_of(kScene);
  RenderSpec r;  // defaults: colour by speed, viridis, automatic range
  r.width = 400;
  r.height = 300;
  const WorldFrame wf = world_frame(w, nullptr, frame_info(w, view_of(kScene), {0.0, -9.81}), r);
  const FrameData f = build_frame(wf.particles, wf.walls, wf.overlays, wf.spec, wf.box);
  // speeds 0, 0.25, 1 m/s: the range is [0, 1] and the colours sit at 0, 1/4, 1 of the map
  EXPECT_EQ(f.value_lo, 0.0);
  EXPECT_DOUBLE_EQ(f.value_hi, 1.0);
  ASSERT_EQ(f.polygons.size(), 3u);
  const Colormap& v = colormap("viridis");
  EXPECT_EQ(f.polygons[0].fill, v.at(0.0));
  EXPECT_EQ(f.polygons[1].fill, v.at(0.25));
  EXPECT_EQ(f.polygons[2].fill, v.at(1.0));
  EXPECT_EQ(f.polygons[1].sides, 7);
  EXPECT_FLOAT_EQ(f.polygons[1].angle, -1.0f);
  // the heptagon's circumradius on the canvas: 0.006 m at the camera's scale
  EXPECT_NEAR(f.polygons[1].radius, 0.006 * f.camera.scale, 1e-3);
  // a fixed range clamps: with [0, 0.2] the two moving grains are both at the top
  r.range = std::array<double, 2>{0.0, 0.2};
  const WorldFrame w2 = world_frame(w, nullptr, frame_info(w, view_of(kScene), {}), r);
  const FrameData f2 = build_frame(w2.particles, w2.walls, w2.overlays, w2.spec, w2.box);
  EXPECT_EQ(f2.polygons[1].fill, v.lut[255]);
  EXPECT_EQ(f2.polygons[2].fill, v.lut[255]);
}

TEST(RenderWorld, OverlaysFollowTheRenderSection) {
  const World w = world_of(kScene);
  RenderSpec r;
  r.test_rect = true;
  r.gravity_arrow = true;
  r.title = "three grains";
  FrameInfo info = frame_info(w, view_of(kScene), {});  // the scene's φ window
  info.time = 1.25;
  info.gravity = {3.0, -4.0};
  const WorldFrame f = world_frame(w, nullptr, info, r);
  ASSERT_TRUE(f.overlays.test_rect);
  EXPECT_EQ(*f.overlays.test_rect, (std::array<double, 4>{0.02, 0.03, 0.18, 0.2}));
  EXPECT_TRUE(f.overlays.show_gravity);
  EXPECT_EQ(f.overlays.gravity, (Vec2{3.0, -4.0}));
  EXPECT_EQ(f.overlays.title, "three grains");
  EXPECT_EQ(f.overlays.time, 1.25);
  EXPECT_TRUE(f.overlays.show_time);
  EXPECT_FALSE(f.overlays.has_tap);  // constant gravity: no taps
  // without them: no rectangle, no arrow, no clock
  RenderSpec none;
  none.clock = false;
  const WorldFrame g = world_frame(w, nullptr, info, none);
  EXPECT_FALSE(g.overlays.test_rect);
  EXPECT_FALSE(g.overlays.show_gravity);
  EXPECT_FALSE(g.overlays.show_time);
  // force chains need the contacts
  RenderSpec chains;
  chains.force_chains = true;
  EXPECT_THROW(world_frame(w, nullptr, info, chains), std::invalid_argument);
}

TEST(RenderWorld, TapNumberAndPhaseFromTheProtocolClock) {
  // negative g with T = 2 s, t1 = 0.01 s, the clock started at 0.5 s (after settling)
  const std::vector<std::string> sets{"drive.kind=negative_g", "drive.period=2.0", "drive.t1=0.01"};
  World w = world_of(kScene, sets);
  const ViewSettings view = view_of(kScene, sets);
  w.clock_origin = 0.5;
  w.s.t = 0.2;
  FrameInfo a = frame_info(w, view, {});
  EXPECT_TRUE(a.settling);
  EXPECT_FALSE(a.tap);
  w.s.t = 0.505;  // inside the first pulse
  FrameInfo b = frame_info(w, view, {});
  EXPECT_TRUE(b.exciting);
  ASSERT_TRUE(b.tap);
  EXPECT_EQ(*b.tap, 1);
  w.s.t = 4.6;  // relaxing after the third pulse
  FrameInfo c = frame_info(w, view, {});
  EXPECT_FALSE(c.exciting);
  EXPECT_EQ(c.tap.value_or(-1), 3);
  RenderSpec r;
  const WorldFrame f = world_frame(w, nullptr, c, r);
  EXPECT_TRUE(f.overlays.has_tap);
  EXPECT_EQ(f.overlays.tap, 3);
  ASSERT_EQ(f.overlays.lines.size(), 1u);
  EXPECT_EQ(f.overlays.lines[0], "relaxing");
}

// two soft disks pressed together by δ = 0.1 mm, and a third resting into the floor
const char* kDisks = R"(
[model]
kind = "S"

[[material]]
name = "glass"
ks = 1e5
eps_n = 0.5
mu = 0.0

[[species]]
name = "bead"
radius = 0.005
mass = 1e-3

[box]
width = 0.1
height = 0.1

[[preparation.particle]]
x = 0.03
y = 0.05

[[preparation.particle]]
x = 0.0399
y = 0.05

[[preparation.particle]]
x = 0.08
y = 0.0049

[drive]
kind = "none"
)";

TEST(RenderWorld, ContactCountsPressureAndChainsFromTheContacts) {
  World w = world_of(kDisks);
  const SimSettings settings = SimSettings::from(parse_scene_string(kDisks, "t.toml", {}));
  const Simulation sim(std::move(w), settings);  // computes the contacts of the initial state
  const World& sw = sim.world();
  const ContactSet& c = sim.contacts();
  EXPECT_EQ(contact_counts(sw, c), (std::vector<double>{1.0, 1.0, 1.0}));
  // at rest the force is the spring's: F = k_s·δ = 1e5 × 1e-4 = 10 N, applied at the middle
  // of the overlap, r − δ/2 from each centre: p = F (r − δ/2) / (2 π r²)
  const double r = 0.005, F = 1e5 * 1e-4, A = M_PI * r * r;
  const auto p = contact_pressure(sw, c);
  EXPECT_NEAR(p[0], F * (r - 0.5e-4) / (2 * A), 1e-9 * F / A);
  EXPECT_NEAR(p[1], p[0], 1e-9 * F / A);
  // the grain on the floor: δ = 0.1 mm too
  EXPECT_NEAR(p[2], p[0], 1e-9 * F / A);
  // chains: centre to centre for the pair, centre to contact point for the wall
  const auto lines = force_chain_lines(sw, c);
  ASSERT_EQ(lines.size(), 2u);
  const auto pair =
      std::find_if(lines.begin(), lines.end(), [](const ContactLine& l) { return l.a.y == 0.05; });
  ASSERT_NE(pair, lines.end());
  EXPECT_NEAR(pair->force, F, 1e-9);
  EXPECT_NEAR(norm(pair->b - pair->a), 0.0099, 1e-12);
  // colouring by pressure carries it as the builder's extra value with its unit
  RenderSpec rs;
  rs.color_by = "pressure";
  rs.force_chains = true;
  const WorldFrame f = world_frame(sw, &c, frame_info(sw, view_of(kDisks), sim.gravity()), rs);
  EXPECT_EQ(f.particles.value_extra, p);
  EXPECT_EQ(f.spec.color_by, ColorBy::extra);
  EXPECT_EQ(f.spec.extra_unit, "N/m");
  EXPECT_EQ(f.overlays.force_chains.size(), 2u);
}

TEST(RenderWorld, SceneNamesAreTheRenderersNames) {
  // every colour map the scene accepts exists, and every map that exists is accepted
  for (auto n : render_colormap_names()) EXPECT_NO_THROW(colormap(std::string(n))) << n;
  for (const auto& n : colormap_names()) {
    const auto names = render_colormap_names();
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  }
  // every colouring the scene accepts gives a frame spec
  for (auto n : render_color_by_names()) {
    RenderSpec r;
    r.color_by = std::string(n);
    EXPECT_NO_THROW(frame_spec(r)) << n;
  }
}

}  // namespace
}  // namespace gs

// the pair loop's contacts are the narrow-phase registry's: for every candidate of a small
// scene (grain pairs, wall pairs, periodic images; polygons and disks), the run-time table's
// function on the same placed bodies decides whether it touches and gives its contact frame,
// bit for bit, as the contact set of ContactModel::evaluate records it
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "broadphase/broadphase.hpp"
#include "contact/narrow.hpp"
#include "contact/placement.hpp"
#include "force/forces.hpp"
#include "scene/parse.hpp"
#include "world/prepare.hpp"
#include "world/world.hpp"

namespace gs {
namespace {

struct Seen {
  int contacts = 0, walls = 0, images = 0;
};

Seen expect_registry_frames(const World& w, const ContactSettings& settings) {
  auto bp = make_broadphase(BroadPhaseKind::CellGrid, w);
  const std::vector<PairKey>& cand = bp->update(w);
  ContactModel model(w, settings);
  ContactSet cs;
  ForceBuffer f;
  ThreadTeam team;
  model.evaluate(w, cand, cs, f, 1e-5, team);
  PlacedPolygons placed(w);
  placed.place(w, 0, placed.begin(w));
  const auto N = static_cast<std::uint32_t>(w.size());
  const BodyKind kind = body_kind(w.species[0].shape);
  Seen seen;
  for (const PairKey key : cand) {
    const std::uint32_t i = key_i(key), j = key_j(key);
    const bool wall = j >= N;
    const PolyRef pi = placed.grain(i);
    const PlacedBody a{{w.s.x[i], w.s.y[i]}, w.radius[i], &pi, {}, nullptr};
    PlacedBody b;
    PolyRef pj;
    if (wall) {
      pj = placed.wall(j - N);
      b = PlacedBody{{}, 0.0, &pj, {}, &w.walls[j - N]};
    } else {
      pj = placed.grain(j);
      const Vec2 own{w.s.x[j], w.s.y[j]};
      const Vec2 c = own + Vec2{image_sx(key_image(key)) * w.Lx, image_sy(key_image(key)) * w.Ly};
      b = PlacedBody{c, w.radius[j], &pj, key_image(key) == kNoImage ? Vec2{} : c - own, nullptr};
    }
    const NarrowFn fn = narrow_fn(kind, wall ? BodyKind::Wall : kind);
    if (fn == nullptr) {
      ADD_FAILURE() << "no narrow phase for this pairing";
      return seen;
    }
    const ContactGeom g = fn(a, b);
    const auto at = std::lower_bound(cs.keys.begin(), cs.keys.end(), key);
    const bool recorded = at != cs.keys.end() && *at == key;
    EXPECT_EQ(g.touching, recorded) << "pair " << i << "–" << j;
    if (!recorded || !g.touching) continue;
    const ContactRecord& r = cs.records[static_cast<std::size_t>(at - cs.keys.begin())];
    EXPECT_EQ(r.s, g.s);
    EXPECT_EQ(r.n, g.n);
    EXPECT_EQ(r.overlap, g.overlap);
    ++seen.contacts;
    seen.walls += wall;
    seen.images += !wall && key_image(key) != kNoImage;
  }
  return seen;
}

// a box of width 0.06 and height 0.1 (walls or periodic), grains of radius 9 mm (decagons or
// disks) pressed into each other, into the floor and, periodic, across the edges
std::string scene(bool polygons, bool periodic) {
  std::string s = "[scene]\nname = \"registry\"\nduration = 0.001\n";
  s += polygons ? "[model]\nkind = \"P\"\n" : "[model]\nkind = \"S\"\nrotation = false\n";
  s += polygons ? "[[material]]\nname = \"m\"\nE = 1000.0\ngamma = 0.5\nmu = 0.6\n"
                : "[[material]]\nname = \"m\"\nks = 5e5\neps_n = 0.5\neps_t = 0.8\nmu = 0.3\n";
  s += polygons ? "[[species]]\nname = \"g\"\nshape = \"polygon\"\nsides = 10\nradius = 0.009\n"
                  "density = 1.0\n"
                : "[[species]]\nname = \"g\"\nshape = \"disk\"\nradius = 0.009\nmass = 1e-3\n";
  s += std::string("[box]\nkind = \"") + (periodic ? "periodic" : "walls") +
       "\"\nwidth = 0.06\nheight = 0.1\n";
  const double xs[][3] = {{0.0095, 0.0085, 0.3}, {0.0265, 0.0088, 1.1}, {0.0420, 0.0095, 0.7},
                          {0.0420, 0.0935, 2.0}, {0.0180, 0.0300, 0.1}, {0.0095, 0.0500, 0.5},
                          {0.0535, 0.0500, 1.7}};
  for (const auto& p : xs)
    s += "[[preparation.particle]]\nspecies = \"g\"\nx = " + std::to_string(p[0]) +
         "\ny = " + std::to_string(p[1]) + "\ntheta = " + std::to_string(p[2]) +
         "\nvx = 0.1\nvy = -0.2\n";
  s += "[integrator]\nkind = \"gear6\"\ndt = 1e-5\n[drive]\nkind = \"none\"\n";
  return s;
}

World world(bool polygons, bool periodic) {
  const SceneSpec s = parse_scene_string(scene(polygons, periodic), "registry");
  World w = make_world(s);
  place_particles(w, s);
  return w;
}

ContactSettings settings(bool polygons, bool periodic) {
  return contact_settings(parse_scene_string(scene(polygons, periodic), "registry"));
}

TEST(PairRegistry, PolygonsInWallsAreTheRegistrys) {
  const Seen s = expect_registry_frames(world(true, false), settings(true, false));
  EXPECT_GE(s.contacts, 4);
  EXPECT_GE(s.walls, 2);
}

TEST(PairRegistry, PolygonImagesAreTheRegistrys) {
  const Seen s = expect_registry_frames(world(true, true), settings(true, true));
  EXPECT_GE(s.contacts, 3);
  EXPECT_GE(s.images, 2);
}

TEST(PairRegistry, DisksInWallsAreTheRegistrys) {
  const Seen s = expect_registry_frames(world(false, false), settings(false, false));
  EXPECT_GE(s.contacts, 4);
  EXPECT_GE(s.walls, 2);
}

TEST(PairRegistry, DiskImagesAreTheRegistrys) {
  const Seen s = expect_registry_frames(world(false, true), settings(false, true));
  EXPECT_GE(s.contacts, 3);
  EXPECT_GE(s.images, 2);
}

}  // namespace
}  // namespace gs

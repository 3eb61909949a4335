// the World: constants (species, walls, box) kept apart from the mutable particle state (SoA)
#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/vec.hpp"
#include "geometry/polygon.hpp"
#include "scene/spec.hpp"

namespace gs {

/// per-species constants, resolved from the scene
struct Species {
  std::string name;
  ShapeKind shape = ShapeKind::Polygon;
  int sides = 0;         ///< n-gon sides (0 for disks)
  double radius = 0.0;   ///< circumradius or disk radius, m
  double area = 0.0;     ///< grain area, m²
  double mass = 0.0;     ///< kg
  double inertia = 0.0;  ///< moment of inertia about the centre, kg m²
  int material = 0;      ///< index into World::materials
  Poly body;             ///< polygon vertices in body coordinates (polygons only), m
};

/// a fixed wall: a convex polygon (rectangle) in world coordinates plus, for disks, the
/// half-plane of its inner face (points x with dot(x, normal) > offset are inside the wall)
struct Wall {
  Poly poly;            ///< world-frame polygon, m
  Vec2 normal;          ///< unit normal of the inner face, pointing into the wall
  double offset = 0.0;  ///< inner face: dot(x, normal) = offset, m
  Vec2 lo, hi;          ///< axis-aligned bounds, m
};

/// mutable particle state, structure of arrays; positions are never wrapped (periodic boxes
/// use the minimum image), so displacements stay continuous for free paths and integrators
struct State {
  std::vector<double> x, y, th;       ///< position (m) and orientation (rad)
  std::vector<double> vx, vy, omega;  ///< velocity (m/s) and angular velocity ω (rad/s)
  std::vector<double> ax, ay, alpha;  ///< accelerations at the current state (m/s², α rad/s²)
  std::vector<int> wrap_x, wrap_y;    ///< periodic boxes: box lengths removed from x, y so far
  double t = 0.0;                     ///< simulated time, s
  std::int64_t step = 0;              ///< steps taken
  std::size_t size() const { return x.size(); }
  void resize(std::size_t n);
};

struct World {
  // constants: what the world is; what the step does with it is the Simulation's settings
  ModelKind model = ModelKind::Polygon;  ///< polygon DEM (Model P) or soft disks (Model S)
  std::vector<MaterialSpec> materials;
  std::vector<Species> species;
  std::vector<Wall> walls;
  int wall_material = 0;
  BoxKind box = BoxKind::Walls;
  double Lx = 0.0, Ly = 0.0;  ///< box inner size (periodic: the period), m
  bool rotation = false;      ///< integrate θ (only when torques can arise)
  double max_radius = 0.0;    ///< largest circumradius, m
  // per-particle constants
  std::vector<int> sp;  ///< species index
  std::vector<double> radius, mass, inv_mass, inv_inertia;
  /// each slot's particle label: its index when it was placed. A periodic spatial sort
  /// (Simulation, integrator.sort_every) moves particles between slots; files list particles
  /// by label, and each particle's random-force stream follows its label.
  std::vector<std::uint32_t> id;
  // mutable state
  State s;
  /// the protocol clock's origin, run state (not a setting): a tapping protocol's schedule
  /// runs on t − clock_origin and gives plain gravity before it (settling). Only the protocol
  /// clock moves it (drive/protocol.hpp); checkpoints save it; it outlives clear_particles, s
  double clock_origin = 0.0;

  std::size_t size() const { return s.size(); }
  bool polygons() const { return model == ModelKind::Polygon; }
  /// append a particle of species k at rest
  void add_particle(int k, Vec2 pos, double theta, Vec2 vel = {}, double omega = 0.0);
  /// remove every particle (constants, species, walls and box stay)
  void clear_particles();
  /// move particles between slots: slot k receives what slot perm[k] held (a permutation
  /// of 0…N−1), in every per-particle array and the state; `scratch` keeps its buffers for
  /// the next call (fresh pages cost more than the copy itself)
  struct PermuteScratch {
    std::vector<double> d;
    std::vector<int> i;
    std::vector<std::uint32_t> u;
  };
  void permute(std::span<const std::uint32_t> perm, PermuteScratch& scratch);
  void permute(std::span<const std::uint32_t> perm) {
    PermuteScratch scratch;
    permute(perm, scratch);
  }
  /// the slot of each label (the inverse of id)
  std::vector<std::uint32_t> slots_by_id() const;
  /// world-frame polygon of particle i (polygons only)
  Poly shape(std::size_t i) const;
  /// kinetic energy (translation + rotation), J
  double kinetic_energy() const;
  /// periodic boxes: bring positions far outside the cell back by whole box lengths (counted
  /// in wrap_x/wrap_y so unwrapped displacements stay available)
  void rewrap(double limit_boxes = 32.0);
  /// unwrapped position of particle i
  Vec2 unwrapped(std::size_t i) const;
  /// minimum-image separation xj − xi (identity in walled boxes)
  Vec2 separation(std::size_t i, std::size_t j) const;
};

/// build the constant part of a World from a validated scene: species, materials, walls, box.
/// No particles yet (see prepare.hpp).
World make_world(const SceneSpec& scene);

}  // namespace gs

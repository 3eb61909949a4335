#include "world/world.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/error.hpp"
#include "core/permute.hpp"

namespace gs {

void State::resize(std::size_t n) {
  for (auto* v : {&x, &y, &th, &vx, &vy, &omega, &ax, &ay, &alpha}) v->resize(n, 0.0);
  wrap_x.resize(n, 0);
  wrap_y.resize(n, 0);
}

void World::rewrap(double limit) {
  if (box == BoxKind::Walls) return;
  for (std::size_t i = 0; i < size(); ++i) {
    if (std::abs(s.x[i]) > limit * Lx) {
      const double k = std::floor(s.x[i] / Lx);
      s.x[i] -= k * Lx;
      s.wrap_x[i] += static_cast<int>(k);
    }
    if (box == BoxKind::Periodic && std::abs(s.y[i]) > limit * Ly) {
      const double k = std::floor(s.y[i] / Ly);
      s.y[i] -= k * Ly;
      s.wrap_y[i] += static_cast<int>(k);
    }
  }
}

Vec2 World::unwrapped(std::size_t i) const {
  return {s.x[i] + s.wrap_x[i] * Lx, s.y[i] + s.wrap_y[i] * Ly};
}

void World::add_particle(int k, Vec2 pos, double theta, Vec2 vel, double omega) {
  const Species& spc = species[k];
  id.push_back(static_cast<std::uint32_t>(sp.size()));
  sp.push_back(k);
  radius.push_back(spc.radius);
  mass.push_back(spc.mass);
  inv_mass.push_back(1.0 / spc.mass);
  inv_inertia.push_back(spc.inertia > 0 ? 1.0 / spc.inertia : 0.0);
  s.x.push_back(pos.x);
  s.y.push_back(pos.y);
  s.th.push_back(theta);
  s.vx.push_back(vel.x);
  s.vy.push_back(vel.y);
  s.omega.push_back(omega);
  s.ax.push_back(0.0);
  s.wrap_x.push_back(0);
  s.wrap_y.push_back(0);
  s.ay.push_back(0.0);
  s.alpha.push_back(0.0);
}

void World::clear_particles() {
  sp.clear();
  radius.clear();
  mass.clear();
  inv_mass.clear();
  inv_inertia.clear();
  id.clear();
  s = State{};
}

// each array keeps its buffer (views onto the World's arrays stay on their quantity)
void World::permute(std::span<const std::uint32_t> perm, PermuteScratch& scratch) {
  if (perm.size() != size()) throw std::invalid_argument("World::permute: wrong size");
  for (auto* v : {&radius, &mass, &inv_mass, &inv_inertia, &s.x, &s.y, &s.th, &s.vx, &s.vy,
                  &s.omega, &s.ax, &s.ay, &s.alpha})
    gather_in_place(*v, perm, scratch.d);
  for (auto* v : {&sp, &s.wrap_x, &s.wrap_y}) gather_in_place(*v, perm, scratch.i);
  gather_in_place(id, perm, scratch.u);
}

std::vector<std::uint32_t> World::slots_by_id() const { return inverse_permutation(id); }

Poly World::shape(std::size_t i) const {
  return place(species[sp[i]].body, {s.x[i], s.y[i]}, s.th[i]);
}

double World::kinetic_energy() const {
  double e = 0.0;
  for (std::size_t i = 0; i < size(); ++i) {
    e += 0.5 * mass[i] * (s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i]);
    if (inv_inertia[i] > 0) e += 0.5 * s.omega[i] * s.omega[i] / inv_inertia[i];
  }
  return e;
}

Vec2 World::separation(std::size_t i, std::size_t j) const {
  Vec2 d{s.x[j] - s.x[i], s.y[j] - s.y[i]};
  if (box == BoxKind::Periodic) {
    d.x -= Lx * std::nearbyint(d.x / Lx);
    d.y -= Ly * std::nearbyint(d.y / Ly);
  } else if (box == BoxKind::Ring1D) {
    d.x -= Lx * std::nearbyint(d.x / Lx);
  }
  return d;
}

namespace {

// a wall rectangle and the inner face it presents to the grains
Wall make_wall(double x0, double y0, double x1, double y1, Vec2 normal, double offset) {
  Wall w;
  w.poly = rectangle(x0, y0, x1, y1);
  w.normal = normal;
  w.offset = offset;
  w.lo = {x0, y0};
  w.hi = {x1, y1};
  return w;
}

int material_index(const SceneSpec& sc, const std::string& name) {
  if (name.empty()) return 0;
  for (std::size_t k = 0; k < sc.materials.size(); ++k)
    if (sc.materials[k].name == name) return static_cast<int>(k);
  throw InputError(sc.path, "material", "unknown material '" + name + "'");
}

}  // namespace

World make_world(const SceneSpec& sc) {
  World w;
  w.model = sc.model.kind;
  w.materials = sc.materials;
  if (w.materials.empty()) w.materials.push_back(MaterialSpec{});
  w.box = sc.box.kind;

  // species: shape, mass and inertia (docs/physics.md §1.1)
  bool any_poly = false, any_disk = false;
  for (const auto& s : sc.species) {
    Species k;
    k.name = s.name;
    k.shape = s.shape;
    k.radius = s.radius;
    k.material = material_index(sc, s.material);
    if (s.shape == ShapeKind::Polygon) {
      any_poly = true;
      k.sides = s.sides;
      k.area = ngon_area(s.sides, s.radius);
      k.mass = s.mass ? *s.mass : s.density * k.area;
      k.inertia = ngon_inertia(s.sides, s.radius, k.mass);
      k.body = regular_polygon(s.sides, s.radius);
    } else {
      any_disk = true;
      k.area = M_PI * s.radius * s.radius;
      k.mass = s.mass ? *s.mass : s.density * k.area;
      k.inertia = disk_inertia(s.radius, k.mass);
    }
    w.max_radius = std::max(w.max_radius, s.radius);
    w.species.push_back(k);
  }
  if (any_poly && any_disk)
    throw InputError(sc.path, "species",
                     "a scene mixes polygons and disks; use one shape kind per scene");
  if (sc.model.kind == ModelKind::Polygon && any_disk)
    throw InputError(sc.path, "model.kind", "model P (polygon DEM) needs polygon species");
  if (sc.model.kind == ModelKind::Disk && any_poly)
    throw InputError(sc.path, "model.kind", "model S (soft disks) needs disk species");

  // rotation only where torques can arise: polygon contacts are non-central
  w.rotation = sc.model.kind == ModelKind::Polygon && sc.model.rotation;

  // box: walls as rectangles around [0,W]×[0,H], or a periodic cell
  w.wall_material = material_index(sc, sc.box.material);
  w.Lx = sc.box.width;
  w.Ly = sc.box.height;
  if (sc.box.kind == BoxKind::Ring1D && sc.box.reduced_length) {
    // the ring's length from the reduced length L′ = L − N·d (docs/physics.md §5.2)
    double occupied = 0.0;
    for (const auto& s : sc.species) occupied += s.count * 2.0 * s.radius;
    w.Lx = *sc.box.reduced_length + occupied;
  }
  if (sc.box.kind == BoxKind::Walls) {
    const double W = sc.box.width, H = sc.box.height, t = sc.box.wall_thickness;
    w.walls.push_back(make_wall(-t, -t, W + t, 0.0, {0, -1}, 0.0));                // floor
    w.walls.push_back(make_wall(-t, 0.0, 0.0, H + t, {-1, 0}, 0.0));               // left
    w.walls.push_back(make_wall(W, 0.0, W + t, H + t, {1, 0}, W));                 // right
    if (sc.box.lid) w.walls.push_back(make_wall(-t, H, W + t, H + t, {0, 1}, H));  // lid
  }
  return w;
}

}  // namespace gs

#include "sim/builders.hpp"

#include <cmath>

#include "geometry/polygon.hpp"

namespace gs::build {

MaterialSpec paper_material() {
  MaterialSpec m;
  m.name = "grain";
  m.E = 1000.0;
  m.gamma = 0.5;
  m.mu = 0.6;
  return m;
}

MaterialSpec disk_material(double eps_n, double eps_t, double ks) {
  MaterialSpec m;
  m.name = "disk";
  m.ks = ks;
  m.eps_n = eps_n;
  m.eps_t = eps_t;
  m.mu = 0.0;
  return m;
}

SceneSpec two_body(ModelKind model, ShapeKind shape, double radius, double mass, int sides,
                   const MaterialSpec& mat, IntegratorKind integ, double dt) {
  SceneSpec s;
  s.name = "two_body";
  s.model.kind = model;
  s.materials = {mat};
  SpeciesSpec sp;
  sp.name = "a";
  sp.shape = shape;
  sp.sides = sides;
  sp.radius = radius;
  sp.mass = mass;
  sp.count = 0;
  sp.material = mat.name;
  s.species = {sp};
  s.box.kind = BoxKind::Periodic;  // no walls; a big periodic cell the pair never crosses
  s.box.width = 1000.0 * radius;
  s.box.height = 1000.0 * radius;
  s.integrator.kind = integ;
  s.integrator.dt = dt;
  s.integrator.broad_phase = BroadPhaseKind::CellGrid;
  s.drive.kind = DriveKind::None;
  s.health.max_overlap = 0.5;
  return s;
}

SceneSpec decagon_pile(int n, double width, double height, std::uint64_t seed) {
  SceneSpec s;
  s.name = "decagon_pile";
  s.model.kind = ModelKind::Polygon;
  s.materials = {paper_material()};
  const int big = static_cast<int>(std::lround(n * 544.0 / 1184.0));
  SpeciesSpec b;
  b.name = "big";
  b.radius = 0.009;
  b.count = big;
  b.material = "grain";
  SpeciesSpec sm = b;
  sm.name = "small";
  sm.radius = 0.00636;
  sm.count = n - big;
  s.species = {b, sm};
  s.box.kind = BoxKind::Walls;
  s.box.width = width;
  s.box.height = height;
  s.box.material = "grain";
  s.prep.placement = PlacementKind::LooseColumn;
  s.prep.seed = seed;
  s.integrator.kind = IntegratorKind::Gear6;
  s.integrator.dt = 5e-5;
  s.drive.kind = DriveKind::Gravity;
  return s;
}

SceneSpec disk_gas(int n, double phi, double eps_n, double eps_t, std::uint64_t seed) {
  SceneSpec s;
  s.name = "disk_gas";
  s.model.kind = ModelKind::Disk;
  s.model.rotation = false;
  s.materials = {disk_material(eps_n, eps_t)};
  SpeciesSpec d;
  d.name = "bead";
  d.shape = ShapeKind::Disk;
  d.radius = 1.5e-3;
  d.mass = 3.53e-5;
  d.count = n;
  d.material = "disk";
  s.species = {d};
  const double L = std::sqrt(n * M_PI * d.radius * d.radius / phi);  // φ = Nπr²/L² (T.2.24)
  s.box.kind = BoxKind::Periodic;
  s.box.width = L;
  s.box.height = L;
  s.prep.placement = PlacementKind::Random;
  s.prep.seed = seed;
  s.prep.velocity_amplitude = 0.1;
  s.integrator.kind = IntegratorKind::VelocityVerlet;
  s.integrator.dt = 1e-6;
  s.integrator.broad_phase = BroadPhaseKind::CellGrid;
  s.drive.kind = DriveKind::None;
  return s;
}

}  // namespace gs::build

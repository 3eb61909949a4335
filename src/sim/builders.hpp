// scene builders shared by tests, benchmarks and demos: SceneSpecs made in code
#pragma once
#include "scene/spec.hpp"

namespace gs::build {

/// the paper's grain material (docs/physics.md §2.2): E = 1000 N/m, γ = 0.5, μ = 0.6
MaterialSpec paper_material();
/// thesis disk material (docs/physics.md §3): k_s = 5·10⁵ N/m, ε_n, ε_t
MaterialSpec disk_material(double eps_n, double eps_t, double ks = 5e5);

/// two explicit particles of one species, no gravity (collision tests)
SceneSpec two_body(ModelKind model, ShapeKind shape, double radius, double mass, int sides,
                   const MaterialSpec& mat, IntegratorKind integ, double dt);

/// a walled box of bidisperse decagons (paper ratio 544:640 of r = 9 mm : 6.36 mm) dropped
/// from a loose column under gravity
SceneSpec decagon_pile(int n, double width, double height, std::uint64_t seed);

/// a periodic box of N equal disks at area fraction φ, thesis particles (docs/physics.md §3)
SceneSpec disk_gas(int n, double phi, double eps_n, double eps_t, std::uint64_t seed);

}  // namespace gs::build

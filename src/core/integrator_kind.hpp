// the names of the time integrators, shared by the scene that chooses one and the integrate/
// module that implements it (integrate/integrator.hpp)
#pragma once
#include <cstdint>
#include <string_view>

namespace gs {

enum class IntegratorKind : std::uint8_t {
  Gear6,              ///< sixth-order Gear predictor–corrector (docs/physics.md §2.3)
  VelocityVerlet,     ///< kick–drift–kick; forces at half-step velocities
  PositionVerlet,     ///< Störmer–Verlet (T.2.3) with a consistent velocity estimate
  SemiImplicitEuler,  ///< symplectic Euler: v += a dt, then x += v dt
};

std::string_view to_string(IntegratorKind k);
/// parse "gear6" | "velocity_verlet" | "position_verlet" | "semi_implicit_euler"; false if unknown
bool parse_integrator(std::string_view s, IntegratorKind& out);
/// the theoretical global order of accuracy for positions on smooth forces
int integrator_order(IntegratorKind k);

}  // namespace gs

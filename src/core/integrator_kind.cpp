// integrator names and orders
#include "core/integrator_kind.hpp"

namespace gs {

// names as they appear in scene files
std::string_view to_string(IntegratorKind k) {
  switch (k) {
    case IntegratorKind::Gear6:
      return "gear6";
    case IntegratorKind::VelocityVerlet:
      return "velocity_verlet";
    case IntegratorKind::PositionVerlet:
      return "position_verlet";
    case IntegratorKind::SemiImplicitEuler:
      return "semi_implicit_euler";
  }
  return "unknown";
}

bool parse_integrator(std::string_view s, IntegratorKind& out) {
  for (auto k : {IntegratorKind::Gear6, IntegratorKind::VelocityVerlet,
                 IntegratorKind::PositionVerlet, IntegratorKind::SemiImplicitEuler}) {
    if (s == to_string(k)) {
      out = k;
      return true;
    }
  }
  return false;
}

// global order of positions and velocities. Gear6 with the customary start r3 = r4 = r5 = 0
// (docs/physics.md §2.3) is second order: the O(Δt³) error in r3 = Δt³·q'''/6 becomes an O(Δt²)
// error in v = r1/Δt after the first correction, and it persists. Its corrector alone is fifth
// order (tests/integrate measures 5.0 with an exact start) and its error constant is small.
int integrator_order(IntegratorKind k) {
  switch (k) {
    case IntegratorKind::Gear6:
      return 2;
    case IntegratorKind::VelocityVerlet:
      return 2;
    case IntegratorKind::PositionVerlet:
      return 2;
    case IntegratorKind::SemiImplicitEuler:
      return 1;
  }
  return 0;
}

}  // namespace gs

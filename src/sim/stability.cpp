#include "sim/stability.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "sim/simulation.hpp"

namespace gs {

double stable_omega_dt(IntegratorKind kind, double zeta) {
  // measured on the damped oscillator (tests/integrate/test_stability.cpp, 0.01 grid)
  double at0 = 2.0, at25 = 1.23;
  switch (kind) {
    case IntegratorKind::Gear6:
      at0 = 0.47;
      at25 = 0.28;
      break;
    case IntegratorKind::VelocityVerlet:
    case IntegratorKind::PositionVerlet:
      at0 = 2.0;
      at25 = 1.23;
      break;
    case IntegratorKind::SemiImplicitEuler:
      at0 = 1.32;
      at25 = 1.40;
      break;
  }
  const double z = std::clamp(zeta, 0.0, 0.5);
  return std::max(0.05, at0 + (at25 - at0) * z / 0.25);
}

StepAdvice time_step_advice(const Simulation& sim) {
  const World& w = sim.world();
  StepAdvice a;
  const double tc = sim.model().min_contact_time();
  a.omega = M_PI / tc;  // ω_d of the stiffest contact; ω₀ is within a few % at these dampings
  a.omega_dt = a.omega * sim.dt();
  // damping ratio: Model P ζ = γ/2; Model S from ε (T.2.6): ζ = −ln ε/√(π² + ln²ε)
  double zeta = 0.0;
  for (const auto& m : w.materials) {
    if (w.polygons()) {
      zeta = std::max(zeta, m.gamma / 2);
    } else if (m.eps_n < 1.0) {
      const double l = std::log(m.eps_n);
      zeta = std::max(zeta, -l / std::sqrt(M_PI * M_PI + l * l));
    }
  }
  const IntegratorKind kind = sim.settings().integrator;
  a.limit = stable_omega_dt(kind, zeta);
  a.suggested_dt = 0.5 * a.limit / a.omega;
  a.stable = a.omega_dt <= a.limit;
  if (!a.stable) {
    std::ostringstream m;
    m << "dt = " << sim.dt() << " s gives omega*dt = " << a.omega_dt
      << " for the stiffest contact (contact time " << tc << " s, damping ratio " << zeta
      << "), beyond the stability limit " << a.limit << " of " << to_string(kind)
      << "; use dt <= " << a.suggested_dt << " s (half the limit)";
    a.message = m.str();
  }
  return a;
}

namespace {

// x rounded down to three significant digits, for advice that stays on the safe side
double round_down(double x) {
  if (!(x > 0.0) || !std::isfinite(x)) return x;
  const double scale = std::pow(10.0, std::floor(std::log10(x)) - 2.0);
  return std::floor(x / scale) * scale;
}

std::string short_number(double v) {
  std::ostringstream m;
  m << v;
  return m.str();
}

// the keys that set the contact time √(m/k): the stiffest material and the lightest grain, so
// that advice about dt names what to change when no practical dt can resolve the contact
std::string contact_time_keys(const SceneSpec& scene) {
  std::ostringstream m;
  const bool p = scene.model.kind == ModelKind::Polygon;
  const MaterialSpec* stiff = nullptr;
  for (const auto& mat : scene.materials)
    if (!stiff || (p ? mat.E > stiff->E : mat.ks > stiff->ks)) stiff = &mat;
  const SpeciesSpec* light = nullptr;
  auto mass = [](const SpeciesSpec& sp) {
    return sp.mass ? *sp.mass : sp.density * sp.radius * sp.radius;  // the scale is what matters
  };
  for (const auto& sp : scene.species)
    if (sp.count > 0 && (!light || mass(sp) < mass(*light))) light = &sp;
  if (stiff)
    m << "material '" << stiff->name << "' " << (p ? "E = " : "ks = ")
      << (p ? stiff->E : stiff->ks);
  if (light)
    m << (stiff ? ", " : "") << "species '" << light->name << "' "
      << (light->mass ? "mass = " + short_number(*light->mass) + " kg"
                      : "density = " + short_number(light->density) + " kg/m²");
  return m.str();
}

}  // namespace

void check_time_step(const Simulation& sim, const SceneSpec& sc) {
  const double dt = sim.dt(), tc = sim.model().min_contact_time();
  // a contact time no practical dt resolves: the stiffness or the mass is the mistake, not dt
  if (!sc.health.allow_unstable && !(tc / 20.0 >= 1e-15))
    throw InputError(sc.path, "integrator.dt",
                     "the stiffest contact lasts " + short_number(tc) +
                         " s, too short for any time step (it is set by " + contact_time_keys(sc) +
                         "): lower the stiffness (ks, or E for Model P) or raise the mass or "
                         "density");
  // the integrator's stability limit on the stiffest contact (above), then the
  // resolution of the contact itself (fewer than 5 steps per contact time)
  if (const StepAdvice adv = time_step_advice(sim); !sc.health.allow_unstable && !adv.stable)
    throw InputError(sc.path, "integrator.dt",
                     adv.message + ", or pass --allow-unstable to run it anyway");
  if (!sc.health.allow_unstable && dt > tc / 5.0) {
    std::ostringstream m;
    m << "dt = " << dt << " s is " << dt / tc << " of the stiffest contact time (" << tc
      << " s); at more than 1/5 the contacts are not resolved and the integration is unstable. "
      << "Use dt <= " << round_down(tc / 5.0) << " s (dt <= " << round_down(tc / 20.0)
      << " s resolves each contact with 20 steps; the contact time is set by "
      << contact_time_keys(sc) << "), or pass --allow-unstable to run it anyway";
    throw InputError(sc.path, "integrator.dt", m.str());
  }
}

}  // namespace gs

// what the Simulation takes of a scene, taken once (Jolt's *Settings): the step's integrator
// and time step, the drive, the health checks, the spatial sort and the contact laws' switches
#pragma once
#include <cstdint>

#include "force/forces.hpp"
#include "scene/spec.hpp"

namespace gs {

/// the periodic health check's thresholds ([health])
struct HealthSettings {
  int check_every = 100;     ///< steps between checks (0 = never)
  double max_overlap = 0.2;  ///< largest overlap tolerated, in grain radii
};

struct SimSettings {
  IntegratorKind integrator = IntegratorKind::Gear6;
  double dt = 5e-5;  ///< time step, s
  /// the broad phase (Auto: the ring's neighbours in 1D, else the cell grid)
  BroadPhaseKind broad_phase = BroadPhaseKind::Auto;
  int sort_every = -1;      ///< spatial sort every K steps (−1 auto, 0 never)
  DriveSpec drive;          ///< gravity, pulses or the random force
  std::uint64_t seed = 1;   ///< the random force's streams are keyed by it
  HealthSettings health;    ///< the periodic health check
  ContactSettings contact;  ///< the contact laws' switches ([model])
  /// the settings of a scene, checked for what the step relies on (a scene made in code has
  /// not been through the parser): InputError naming the scene file and key
  static SimSettings from(const SceneSpec& scene);
};

}  // namespace gs

#include "sim/sim_settings.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace gs {

SimSettings SimSettings::from(const SceneSpec& scene) {
  SimSettings s;
  s.integrator = scene.integrator.kind;
  s.dt = scene.integrator.dt;
  s.broad_phase = scene.integrator.broad_phase;
  s.sort_every = scene.integrator.sort_every;
  s.drive = scene.drive;
  s.seed = scene.prep.seed;
  s.health = {scene.health.check_every, scene.health.max_overlap};
  s.contact = contact_settings(scene);
  auto refuse = [&](const char* key, const std::string& what) {
    throw InputError(scene.path, key, what);
  };
  if (!(s.dt > 0.0) || !std::isfinite(s.dt))
    refuse("integrator.dt",
           "must be a positive, finite time step (got " + std::to_string(s.dt) + " s)");
  if (s.sort_every < -1) refuse("integrator.sort_every", "must be -1 (auto), 0 or more");
  if (s.health.check_every < 0) refuse("health.check_every", "must be 0 or more");
  if (!(s.health.max_overlap > 0.0)) refuse("health.max_overlap", "must be positive");
  if (s.drive.com_removal_every < 0) refuse("drive.com_removal_every", "must be 0 or more");
  return s;
}

}  // namespace gs

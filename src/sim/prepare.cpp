#include "sim/prepare.hpp"

#include <utility>

#include "sim/run_bounds.hpp"
#include "sim/saved_state.hpp"
#include "sim/sim_settings.hpp"
#include "sim/stability.hpp"
#include "world/prepare.hpp"

namespace gs {

PreparedRun prepare_run(SceneSpec scene) {
  PreparedRun r;
  std::optional<SavedState> saved;
  if (!scene.prep.from_state.empty()) {
    saved = read_saved_state(scene);
    fit_scene_to_state(scene, *saved);
  }
  check_run_bounds(scene, ProtocolClock(scene).nominal_duration());
  World world = make_world(scene);
  if (saved)
    place_saved_state(world, *saved);
  else
    place_particles(world, scene);
  r.clock = std::make_unique<ProtocolClock>(scene);
  r.clock->start(world);
  r.sim = std::make_unique<Simulation>(std::move(world), SimSettings::from(scene));
  if (saved) {
    const bool history = take_saved_history(*r.sim, *saved);
    r.from_state = StateOrigin{saved->path, saved->size(), saved->checkpoint.has_value(), history};
  }
  check_time_step(*r.sim, scene);
  r.scene = std::move(scene);
  return r;
}

}  // namespace gs

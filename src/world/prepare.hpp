// initial placement of the grains (docs/physics.md §2.4, §5.1; thesis fig. 2.4):
// deterministic from the seed
#pragma once
#include "world/world.hpp"

namespace gs {

/// add every species' grains to the world (made from `scene`) at the scene's placement
/// ([preparation]: counts, rule, seed), with initial velocities. Throws InputError when the
/// grains do not fit.
void place_particles(World& w, const SceneSpec& scene);

}  // namespace gs

// every count a run derives from its scene — steps, taps, frames, particles, memory — is
// checked before the run allocates or places anything, with an estimate in the message
#pragma once
#include "scene/spec.hpp"

namespace gs {

/// throws InputError naming the scene file and the key(s) that make a derived quantity
/// impossible: too many steps, a tap shorter than a step, too many frames or trajectory bytes,
/// more memory than the machine has (particles, species pairs). `nominal`: the simulated time
/// the run covers (ProtocolClock::nominal_duration), s
void check_run_bounds(const SceneSpec& scene, double nominal);

}  // namespace gs

// which observers a run gets, decided from its scene (tapping, RFM, rendering …)
#pragma once
#include "scene/spec.hpp"
#include "sim/observer.hpp"

namespace gs {

/// the observers a scene asks for; each feature adds its own line in observers.cpp
Observers make_observers(const SceneSpec& scene);

}  // namespace gs

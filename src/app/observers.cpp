#include "app/observers.hpp"

#include "measure/tap_observer.hpp"

namespace gs {

Observers make_observers(const SceneSpec& scene) {
  Observers obs;
  // each feature appends its observers here
  // tapping (negative g, rotating g): taps.csv and segregation.csv, one row per tap
  if (auto tap = make_tap_observer(scene)) obs.push_back(std::move(tap));
  return obs;
}

}  // namespace gs

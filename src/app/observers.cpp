#include "app/observers.hpp"

namespace gs {

Observers make_observers(const SceneSpec& /*scene*/) {
  Observers obs;
  // each feature appends its observers here, e.g.
  //   if (scene.drive.kind == DriveKind::NegativeG) obs.push_back(make_tap_observer(scene));
  return obs;
}

}  // namespace gs

#include "force/forces.hpp"

#include <algorithm>

namespace gs {

ContactSettings contact_settings(const SceneSpec& scene) {
  return {scene.model.hdot_finite_difference, scene.model.rocking_damping,
          scene.model.clip_attractive};
}

ContactModel::ContactModel(const World& w, const ContactSettings& settings)
    : polygons_(w, settings), disks_(w, settings) {
  // the stiffest contact: Model S exact; Model P linearised for flat faces
  const std::size_t nsp = w.species.size();
  min_contact_time_ = 1e300;
  for (std::size_t a = 0; a < nsp; ++a)
    for (std::size_t b = 0; b <= nsp; ++b)
      min_contact_time_ = std::min(min_contact_time_, w.species[a].shape == ShapeKind::Disk
                                                          ? disks_.contact_time(w, a, b)
                                                          : polygons_.contact_time(w, a, b));
}

}  // namespace gs

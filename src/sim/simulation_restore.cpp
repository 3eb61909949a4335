// checkpoint restore hook (the persistent contact set is the only step-to-step history the
// Simulation keeps apart from the World and the integrator) and the restart after an edit
#include "sim/simulation.hpp"

namespace gs {

// keep the observer records of the constructor's evaluation only while they still line up
void Simulation::restore_contacts(ContactSet c) {
  if (c.records.size() != c.keys.size()) {
    if (contacts_.records.size() == c.keys.size())
      c.records = contacts_.records;
    else
      c.records.clear();
  }
  contacts_ = std::move(c);
}

void Simulation::restart_from_state() {
  // as the constructor does, on the World as it now is
  contacts_ = ContactSet{};
  evaluate_start();
  auto ch = channels();
  integ_->init(ch, dt_);
  take_energy_yardstick();
}

}  // namespace gs

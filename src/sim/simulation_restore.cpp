// checkpoint restore hook: the persistent contact set is the only step-to-step history the
// Simulation keeps apart from the World and the integrator
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

}  // namespace gs

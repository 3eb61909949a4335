// a study's cost per particle-step, measured on the machine that will run it
#include "app/reproduce/pile_cost.hpp"

#include <omp.h>

#include <utility>

#include "scene/parse.hpp"
#include "sim/simulation.hpp"
#include "sim/state_file.hpp"
#include "world/prepare.hpp"

namespace gs {

PileCost measure_pile_cost(const std::string& scene, const std::string& state, int steps,
                           const std::function<double()>& cpu_seconds) {
  const SceneSpec s = parse_scene_file(scene);
  World w = make_world(s);
  if (state.empty())
    place_particles(w, s);
  else
    read_state_file(w, state);
  const int particles = static_cast<int>(w.size());
  // one thread: the study runs each run on one core, and CPU time adds up over threads
  const int before = omp_get_max_threads();
  omp_set_num_threads(1);
  Simulation sim(std::move(w), SimSettings::from(s));
  sim.run(1);  // the contact set and the broad phase's tree are built on the first step
  const double t0 = cpu_seconds();
  sim.run(steps);
  const double t1 = cpu_seconds();
  omp_set_num_threads(before);
  PileCost c;
  c.steps = steps;
  c.particles = particles;
  if (steps > 0 && particles > 0 && t1 > t0) {
    c.seconds = (t1 - t0) / (static_cast<double>(steps) * particles);
    c.measured = true;
  }
  return c;
}

}  // namespace gs

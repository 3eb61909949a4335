// a small fixture so physics tests read like short stories
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>

#include "sim/builders.hpp"
#include "sim/simulation.hpp"
#include "world/prepare.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs::testing {

// k OpenMP threads for the scope (ctest runs with OMP_NUM_THREADS=1, which would leave the
// parallel path untested); without OpenMP the serial path is all there is
struct Threads {
#ifdef _OPENMP
  int before = omp_get_max_threads();
  explicit Threads(int k) { omp_set_num_threads(k); }
  ~Threads() { omp_set_num_threads(before); }
#else
  explicit Threads(int) {}
#endif
};

/// FNV-1a over the bytes of the state arrays (positions, angles, velocities)
inline std::uint64_t state_hash(const World& w) {
  std::uint64_t h = 1469598103934665603ULL;
  for (const auto* v : {&w.s.x, &w.s.y, &w.s.th, &w.s.vx, &w.s.vy, &w.s.omega}) {
    const auto* p = reinterpret_cast<const unsigned char*>(v->data());
    for (std::size_t k = 0; k < v->size() * sizeof(double); ++k) h = (h ^ p[k]) * 1099511628211ULL;
  }
  return h;
}

/// a Simulation built from a scene; explicit particles may be added before start()
struct TestWorld {
  SceneSpec scene;
  std::unique_ptr<Simulation> sim;

  explicit TestWorld(SceneSpec s) : scene(std::move(s)) {}
  TestWorld& particle(double x, double y, double vx, double vy, double theta = 0.0,
                      double omega = 0.0) {
    scene.prep.particles.push_back({scene.species[0].name, x, y, theta, vx, vy, omega});
    return *this;
  }
  Simulation& start() {
    World w = make_world(scene);
    place_particles(w, scene);
    sim = std::make_unique<Simulation>(std::move(w), SimSettings::from(scene));
    return *sim;
  }
  World& world() { return sim->world(); }
  Vec2 v(std::size_t i) const { return {sim->world().s.vx[i], sim->world().s.vy[i]}; }
  Vec2 x(std::size_t i) const { return {sim->world().s.x[i], sim->world().s.y[i]}; }
  Vec2 momentum() const {
    const World& w = sim->world();
    Vec2 p;
    for (std::size_t i = 0; i < w.size(); ++i) p += Vec2{w.s.vx[i], w.s.vy[i]} * w.mass[i];
    return p;
  }
  /// step until the contact set has been non-empty and is empty again (or max steps)
  bool run_through_collision(std::int64_t max_steps) {
    bool touched = false;
    for (std::int64_t k = 0; k < max_steps; ++k) {
      sim->step();
      const bool now = !sim->contacts().keys.empty();
      if (now) touched = true;
      if (touched && !now) return true;
    }
    return false;
  }
};

}  // namespace gs::testing

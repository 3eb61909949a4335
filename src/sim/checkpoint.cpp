#include "sim/checkpoint.hpp"

#include <cmath>
#include <cstring>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/bytes.hpp"
#include "core/error.hpp"
#include "scene/parse.hpp"
#include "world/prepare.hpp"

namespace gs {

// payload in the order of docs/robustness.md, then the header in front
std::string encode_checkpoint(const Simulation& sim, const SceneSpec& scene,
                              const CheckpointExtras& extras) {
  const World& w = sim.world();
  const State& s = w.s;
  ByteWriter p;
  p.str(scene_to_toml(scene));
  p.f64(w.clock_origin);
  p.f64(s.t);
  p.i64(s.step);
  p.u64(w.size());
  p.i32s(w.sp);
  for (const auto* v : {&w.radius, &w.mass, &w.inv_mass, &w.inv_inertia, &s.x, &s.y, &s.th, &s.vx,
                        &s.vy, &s.omega, &s.ax, &s.ay, &s.alpha})
    p.f64s(*v);
  p.i32s(s.wrap_x);
  p.i32s(s.wrap_y);
  p.i32s(std::vector<std::int32_t>(w.id.begin(), w.id.end()));
  // integrator history
  const Integrator& integ = sim.integrator();
  p.u8(static_cast<std::uint8_t>(integ.kind()));
  const std::vector<double> hist = integ.save();
  p.u64(hist.size());
  p.f64s(hist);
  // persistent contacts
  const ContactSet& cs = sim.contacts();
  p.u64(cs.degenerate);
  p.u64(cs.keys.size());
  for (PairKey k : cs.keys) p.u64(k);
  p.u64(cs.state.size());
  for (const ContactState& c : cs.state) {
    p.f64(c.spring.spring);
    p.f64(c.spring.v_prev);
    p.f64(c.h_prev);
  }
  // opaque extras, key order
  p.u64(extras.entries.size());
  for (const auto& [k, v] : extras.entries) {
    p.str(k);
    p.str(v);
  }
  ByteWriter h;
  h.out.append(kCheckpointMagic, 8);
  h.u32(kCheckpointVersion);
  h.u32(kCheckpointEndian);
  h.u64(p.out.size());
  h.u64(fnv1a64(p.out));
  return h.out + p.out;
}

void write_checkpoint(const Simulation& sim, const SceneSpec& scene, const CheckpointExtras& extras,
                      const std::string& path) {
  write_file_atomic(path, encode_checkpoint(sim, scene, extras));
}

SceneSpec checkpoint_scene(const Checkpoint& c) {
  return parse_scene_string(c.scene_toml, c.path + " (embedded scene)");
}

Simulation restore_simulation(const Checkpoint& c) {
  const SceneSpec scene = checkpoint_scene(c);
  if (c.integrator != static_cast<std::uint8_t>(scene.integrator.kind))
    throw InputError(c.path, "integrator.kind", "checkpoint history is for another integrator");
  // the World's constants from the scene, the particles from the file
  World w = make_world(scene);
  const std::size_t n = c.sp.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (c.sp[i] < 0 || static_cast<std::size_t>(c.sp[i]) >= w.species.size())
      throw InputError(
          c.path, "",
          "particle " + std::to_string(i) + " has unknown species " + std::to_string(c.sp[i]));
    for (const auto* v : {&c.s.x, &c.s.y, &c.s.th, &c.s.vx, &c.s.vy, &c.s.omega, &c.s.ax, &c.s.ay,
                          &c.s.alpha, &c.radius, &c.mass, &c.inv_mass, &c.inv_inertia})
      if (!std::isfinite((*v)[i]))
        throw InputError(c.path, "", "particle " + std::to_string(i) + " has a non-finite value");
    w.add_particle(c.sp[i], {c.s.x[i], c.s.y[i]}, c.s.th[i]);
  }
  if (!std::isfinite(c.s.t) || c.s.step < 0) throw InputError(c.path, "", "bad time or step count");
  // a run's time is its step count times dt: anything else (a time of 10³⁸ s) would overflow
  // the protocol's tap count
  const double t_steps = static_cast<double>(c.s.step) * scene.integrator.dt;
  if (c.s.step > 1'000'000'000'000'000 ||
      !(std::abs(c.s.t - t_steps) <= 1e-9 * std::max(1.0, std::abs(t_steps))))
    throw InputError(c.path, "",
                     "the time t = " + std::to_string(c.s.t) + " s is not step " +
                         std::to_string(c.s.step) + " × integrator.dt");
  // per-grain constants: positive, and for polygons exactly the species' (the contact model's
  // pair constants stand for every grain of a species)
  for (std::size_t i = 0; i < n; ++i) {
    const Species& k = w.species[static_cast<std::size_t>(c.sp[i])];
    const bool positive =
        c.radius[i] > 0 && c.mass[i] > 0 && c.inv_mass[i] > 0 && c.inv_inertia[i] >= 0;
    const bool species =
        !w.polygons() ||
        (c.radius[i] == k.radius && c.mass[i] == k.mass && c.inv_mass[i] == 1.0 / k.mass &&
         c.inv_inertia[i] == (k.inertia > 0 ? 1.0 / k.inertia : 0.0));
    if (!positive || !species)
      throw InputError(c.path, "",
                       "particle " + std::to_string(i) +
                           " has a radius, mass or inertia that is not its species' "
                           "(species '" +
                           k.name + "')");
  }
  w.sp.assign(c.sp.begin(), c.sp.end());
  w.id.assign(c.id.begin(), c.id.end());
  w.radius = c.radius;
  w.mass = c.mass;
  w.inv_mass = c.inv_mass;
  w.inv_inertia = c.inv_inertia;
  w.s = c.s;
  w.clock_origin = c.clock_origin;
  // the constructor evaluates forces (and contacts) afresh; the stored history then replaces
  // what that evaluation produced, so the next step sees exactly the saved state
  Simulation sim(std::move(w), SimSettings::from(scene));
  load_checkpoint_history(sim, c, true);
  return sim;
}

void load_checkpoint_history(Simulation& sim, const Checkpoint& c, bool degenerate_count) {
  State& s = sim.world().s;
  s.ax = c.s.ax;
  s.ay = c.s.ay;
  s.alpha = c.s.alpha;
  sim.integrator().load(c.integ);
  ContactSet cs;
  cs.keys = c.keys;
  cs.state = c.contact_state;
  if (degenerate_count) cs.degenerate = c.degenerate;
  sim.restore_contacts(std::move(cs));
}

}  // namespace gs

// preparation.from_state: a scene's grains taken from a saved state (a state file, a
// checkpoint, or a run directory) instead of being placed. The scene gives species, materials
// and box; the saved state gives the grains, and a checkpoint also the integrator's history
// and the contact springs, so a run forked from it continues bitwise (docs/scene-format.md).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "scene/spec.hpp"
#include "sim/checkpoint.hpp"
#include "sim/simulation.hpp"
#include "world/world.hpp"

namespace gs {

/// the grains of a saved state, in the slot order they are placed in
struct SavedState {
  std::string path;                  ///< the file read (a run directory resolved)
  std::vector<std::string> species;  ///< species name of each grain
  std::vector<std::string> where;    ///< "file:line" (state file) or "file" of each grain
  std::vector<double> x, y, th, vx, vy, omega;
  std::optional<Checkpoint> checkpoint;  ///< set when read from a checkpoint
  std::optional<SceneSpec> embedded;     ///< the checkpoint's own scene, parsed once
  std::size_t size() const { return x.size(); }
};

/// read scene.prep.from_state: a state file, a checkpoint (GSCKPT magic), or a run directory
/// (the later of its newest readable checkpoint and its state.csv). InputError naming the
/// scene's file, line and key when the path cannot be read
SavedState read_saved_state(const SceneSpec& scene);

/// check the saved grains against the scene (species by name, the counts given, the box) and
/// set the counts left out; InputError naming file, line and key of the mismatch
void fit_scene_to_state(SceneSpec& scene, const SavedState& st);

/// add the saved grains to `w` (made from the fitted scene; no particles yet)
void place_saved_state(World& w, const SavedState& st);

/// a checkpoint's history, for a Simulation just constructed from place_saved_state's World:
/// accelerations, integrator history and persistent contacts (with their springs), when the
/// scene keeps the checkpoint's integrator, time step and contact model; returns whether it did
bool take_saved_history(Simulation& sim, const SavedState& st);

}  // namespace gs

// a scene made ready to run: the one way the run command and the Python module build their
// simulation, so that both place the same grains and refuse the same scenes
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "drive/protocol.hpp"
#include "scene/spec.hpp"
#include "sim/simulation.hpp"

namespace gs {

/// where the grains of a scene with preparation.from_state came from
struct StateOrigin {
  std::string path;         ///< the file read (a run directory resolved to one of its files)
  std::size_t grains = 0;   ///< how many grains it gave
  bool checkpoint = false;  ///< it was a checkpoint
  bool history = false;     ///< its integrator history and contact springs were taken too
};

struct PreparedRun {
  /// the scene as it runs: the parsed one, with the counts it left out taken from the saved
  /// state (scene.toml of the run directory is written from it)
  SceneSpec scene;
  std::unique_ptr<ProtocolClock> clock;
  std::unique_ptr<Simulation> sim;
  std::optional<StateOrigin> from_state;
};

/// every count the scene derives is checked before anything is allocated (run_bounds.hpp); the
/// grains are placed, or taken from preparation.from_state (read once); the protocol clock starts
/// before the first force evaluation, so the initial accelerations see settling gravity; an
/// unstable time step is refused (unless health.allow_unstable). InputError naming the scene's
/// file, line and key on any of these
PreparedRun prepare_run(SceneSpec scene);

}  // namespace gs

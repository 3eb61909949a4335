// saved states for `gransim render` and `gransim movie`: a run directory (scene.toml +
// state.csv), a state file with its scene, or a frame of a trajectory. Each kind is one
// SnapshotReader in a table, so a checkpoint reader plugs in with one more entry.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/vec.hpp"
#include "world/world.hpp"

namespace gs {

/// what the caller asks for
struct SnapshotRequest {
  std::string scene;              ///< scene file ("" = the scene.toml beside the input)
  std::vector<std::string> sets;  ///< --set overrides applied to the scene
  int frame = -1;                 ///< trajectory frame (0-based; −1 = the last)
};

/// a saved state with its scene
struct Snapshot {
  SceneSpec scene;              ///< the scene it was made with
  World world;                  ///< constants from the scene, particles from the file
  std::string source;           ///< the file the particles came from
  std::string kind;             ///< which reader read it ("run directory", "state file", …)
  std::optional<Vec2> gravity;  ///< gravity as recorded (trajectories), m/s²
  std::optional<long> tap;      ///< tap number as recorded (trajectories)
};

/// one kind of saved state: does it recognise the path, and how to read it
struct SnapshotReader {
  std::string kind;
  std::function<bool(const std::filesystem::path&)> accepts;
  std::function<Snapshot(const std::filesystem::path&, const SnapshotRequest&)> read;
};

/// the readers tried in order: checkpoint (.gsck), run directory without a final state (its
/// newest checkpoint), run directory, state file (.csv), trajectory (.xyz)
const std::vector<SnapshotReader>& snapshot_readers();

/// read whatever `path` is; InputError when no reader accepts it or it cannot be read
Snapshot load_snapshot(const std::string& path, const SnapshotRequest& req);

/// the scene of an input: req.scene, else DIR/scene.toml for a directory or the scene.toml
/// beside a file; InputError saying to pass --scene when there is none
std::string scene_for(const std::filesystem::path& input, const SnapshotRequest& req);

/// a Snapshot of the scene at `scene_path` (with `sets`): its World without particles, the
/// tapping protocol clock started as a run starts it (settling first), so that gravity and tap
/// phase follow the schedule; `source` and `kind` say where the particles will come from
Snapshot scene_snapshot(const std::string& scene_path, const std::vector<std::string>& sets,
                        const std::string& source, const std::string& kind);

}  // namespace gs

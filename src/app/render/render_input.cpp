// the saved-state readers behind `gransim render` and `gransim movie`
#include "app/render/render_input.hpp"

#include "app/run/run_session.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "drive/protocol.hpp"
#include "output/particles/trajectory.hpp"
#include "scene/parse.hpp"
#include "sim/state_file.hpp"

namespace gs {

namespace fs = std::filesystem;

std::string scene_for(const fs::path& input, const SnapshotRequest& req) {
  if (!req.scene.empty()) return req.scene;
  const fs::path dir = fs::is_directory(input) ? input : input.parent_path();
  const fs::path s = (dir.empty() ? fs::path(".") : dir) / "scene.toml";
  if (fs::exists(s)) return s.string();
  throw InputError(input.string(), "",
                   "no scene.toml beside it; pass the scene it was made with: --scene SCENE");
}

Snapshot scene_snapshot(const std::string& scene_path, const std::vector<std::string>& sets,
                        const std::string& source, const std::string& kind) {
  Snapshot s;
  s.scene = parse_scene_file(scene_path, sets);
  s.world = make_world(s.scene);
  // the protocol clock as a run starts it: settling first, then the schedule
  ProtocolClock(s.scene).start(s.world);
  s.source = source;
  s.kind = kind;
  return s;
}

namespace {

// a state file (state.csv) with its scene
Snapshot read_state(const fs::path& file, const SnapshotRequest& req) {
  Snapshot s = scene_snapshot(scene_for(file, req), req.sets, file.string(), "state file");
  read_state_file(s.world, file.string());
  return s;
}

// frame req.frame (−1: the last) of a trajectory, with its scene
Snapshot read_trajectory(const fs::path& file, const SnapshotRequest& req) {
  Snapshot s = scene_snapshot(scene_for(file, req), req.sets, file.string(), "trajectory");
  TrajectoryReader in(file.string());
  TrajectoryFrame f, last;
  bool any = false;
  while (in.next(f)) {
    any = true;
    last = std::move(f);
    if (req.frame >= 0 && in.frames() == req.frame + 1) break;
  }
  if (!any) throw InputError(file.string(), "", "the trajectory holds no frame");
  if (req.frame >= 0 && in.frames() != req.frame + 1)
    throw InputError(file.string(), "--frame",
                     "asked for frame " + std::to_string(req.frame) + " but the trajectory has " +
                         std::to_string(in.frames()) + " (0 … " + std::to_string(in.frames() - 1) +
                         ")");
  load_trajectory_frame(s.world, last, file.string());
  s.gravity = last.gravity;
  s.tap = last.tap;
  return s;
}

// a checkpoint: the complete state, with the scene it embeds (--scene/--set are not needed;
// --set still applies to what only drawing uses)
Snapshot read_checkpoint_file(const fs::path& file, const SnapshotRequest&) {
  const Checkpoint c = read_checkpoint(file.string());
  Simulation sim = restore_simulation(c);
  Snapshot s{checkpoint_scene(c), sim.world(), file.string(), "checkpoint", sim.gravity(), {}};
  const DrivePhase p = drive_phase(s.scene.drive, s.world.clock_origin, s.world.s.t);
  if (is_tapping(s.scene.drive) && !p.settling) s.tap = p.tap;
  return s;
}

bool has_ext(const fs::path& p, const char* ext) {
  return fs::is_regular_file(p) && p.extension() == ext;
}

}  // namespace

const std::vector<SnapshotReader>& snapshot_readers() {
  static const std::vector<SnapshotReader> readers = {
      // a checkpoint file, and a run directory without a final state (killed): its newest
      // valid checkpoint
      {"checkpoint", [](const fs::path& p) { return has_ext(p, ".gsck"); }, read_checkpoint_file},
      {"run directory (checkpoint)",
       [](const fs::path& p) {
         return fs::is_directory(p) && !fs::exists(p / "state.csv") &&
                !list_checkpoints(p.string()).empty();
       },
       [](const fs::path& p, const SnapshotRequest& r) {
         const Checkpoint c = newest_valid_checkpoint(p.string());
         Snapshot s = read_checkpoint_file(c.path, r);
         s.kind = "run directory (checkpoint)";
         return s;
       }},
      // a run directory: its final state
      {"run directory",
       [](const fs::path& p) { return fs::is_directory(p) && fs::exists(p / "state.csv"); },
       [](const fs::path& p, const SnapshotRequest& r) {
         Snapshot s = read_state(p / "state.csv", r);
         s.kind = "run directory";
         return s;
       }},
      {"state file", [](const fs::path& p) { return has_ext(p, ".csv"); }, read_state},
      {"trajectory", [](const fs::path& p) { return has_ext(p, ".xyz"); }, read_trajectory},
  };
  return readers;
}

Snapshot load_snapshot(const std::string& path, const SnapshotRequest& req) {
  const fs::path p(path);
  if (!fs::exists(p)) throw InputError(path, "", "no such file or directory");
  // a FIFO or a device would block or never end: named as such before any reader opens it
  if (!fs::is_directory(p)) check_input_file(path, "saved state");
  for (const SnapshotReader& r : snapshot_readers())
    if (r.accepts(p)) return r.read(p, req);
  std::string kinds;
  for (const SnapshotReader& r : snapshot_readers()) kinds += (kinds.empty() ? "" : ", ") + r.kind;
  throw InputError(path, "",
                   "not a saved state gransim can read (known: " + kinds +
                       "; a run directory needs its state.csv)");
}

}  // namespace gs

#include "sim/saved_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "scene/parse.hpp"
#include "sim/state_file.hpp"

namespace gs {

namespace fs = std::filesystem;

namespace {

constexpr const char* kKey = "preparation.from_state";

// does the file begin with the checkpoint magic?
bool is_checkpoint_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[8] = {};
  in.read(head, sizeof head);
  return in.gcount() == 8 && std::memcmp(head, kCheckpointMagic, 8) == 0;
}

SavedState from_state_rows(const std::string& path) {
  StateRows r = read_state_rows(path);
  SavedState st;
  st.path = path;
  st.species = std::move(r.species);
  for (int l : r.line) st.where.push_back(path + ":" + std::to_string(l));
  st.x = std::move(r.x);
  st.y = std::move(r.y);
  st.th = std::move(r.th);
  st.vx = std::move(r.vx);
  st.vy = std::move(r.vy);
  st.omega = std::move(r.omega);
  return st;
}

SavedState from_checkpoint(Checkpoint c) {
  SavedState st;
  st.path = c.path;
  // species indices name the species of the scene the checkpoint carries
  const SceneSpec& embedded =
      st.embedded.emplace(parse_scene_string(c.scene_toml, c.path + " (embedded scene)"));
  for (std::size_t i = 0; i < c.sp.size(); ++i) {
    if (c.sp[i] < 0 || static_cast<std::size_t>(c.sp[i]) >= embedded.species.size())
      throw InputError(
          c.path, "",
          "particle " + std::to_string(i) + " has unknown species " + std::to_string(c.sp[i]));
    st.species.push_back(embedded.species[static_cast<std::size_t>(c.sp[i])].name);
    st.where.push_back(c.path + " (particle in slot " + std::to_string(i) + ")");
  }
  st.x = c.s.x;
  st.y = c.s.y;
  st.th = c.s.th;
  st.vx = c.s.vx;
  st.vy = c.s.vy;
  st.omega = c.s.omega;
  st.checkpoint = std::move(c);
  return st;
}

// a run directory: its newest readable checkpoint, or its state.csv when that is later
SavedState from_run_dir(const std::string& dir, const std::string& where) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string n = e.path().filename().string();
    if (n.rfind("checkpoint-", 0) == 0 && n.size() > 16 && n.compare(n.size() - 5, 5, ".gsck") == 0)
      names.push_back(e.path().string());
  }
  std::sort(names.rbegin(), names.rend());  // zero-padded steps: newest first
  std::optional<Checkpoint> ck;
  for (const std::string& p : names) {
    try {
      ck = read_checkpoint(p);
      break;
    } catch (const InputError&) {
      // a damaged newest checkpoint: the one before it
    }
  }
  const std::string state = (fs::path(dir) / "state.csv").string();
  const bool have_state = fs::exists(state, ec);
  if (ck && (!have_state || ck->s.step >= read_state_rows(state).step))
    return from_checkpoint(std::move(*ck));
  if (have_state) return from_state_rows(state);
  throw InputError(
      where, kKey,
      "the run directory " + dir + " has neither a readable checkpoint nor a state.csv");
}

}  // namespace

SavedState read_saved_state(const SceneSpec& scene) {
  const std::string& path = scene.prep.from_state;
  const std::string& where = scene.prep.from_state_where;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(where, kKey, "no such file or directory: " + path);
  if (fs::is_directory(path, ec)) return from_run_dir(path, where);
  if (is_checkpoint_file(path)) return from_checkpoint(read_checkpoint(path));
  return from_state_rows(path);
}

void fit_scene_to_state(SceneSpec& scene, const SavedState& st) {
  const std::string& where = scene.prep.from_state_where;
  // species by name
  std::vector<std::int64_t> count(scene.species.size(), 0);
  for (std::size_t i = 0; i < st.size(); ++i) {
    std::size_t k = 0;
    while (k < scene.species.size() && scene.species[k].name != st.species[i]) ++k;
    if (k == scene.species.size()) {
      std::string names;
      for (const auto& sp : scene.species) names += (names.empty() ? "'" : ", '") + sp.name + "'";
      throw InputError(where, kKey,
                       "the saved state's grain at " + st.where[i] + " is of species '" +
                           st.species[i] + "', which this scene does not define (it defines " +
                           names + ")");
    }
    ++count[k];
  }
  if (st.size() == 0)
    throw InputError(where, kKey, "the saved state " + st.path + " has no grains");
  // counts: a given one must match, a missing one is taken
  for (std::size_t k = 0; k < scene.species.size(); ++k) {
    SpeciesSpec& sp = scene.species[k];
    if (sp.count_given && sp.count != count[k])
      throw InputError(scene.path + ":" + std::to_string(sp.line),
                       "species[" + std::to_string(k) + "].count",
                       "is " + std::to_string(sp.count) + " but the saved state " + st.path +
                           " has " + std::to_string(count[k]) + " grains of species '" + sp.name +
                           "' (leave count out to take the saved state's)");
    sp.count = static_cast<int>(count[k]);
  }
  // the box must hold every grain centre (periodic boxes and rings take any position)
  if (scene.box.kind == BoxKind::Walls) {
    const double W = scene.box.width, H = scene.box.height;
    for (std::size_t i = 0; i < st.size(); ++i) {
      const bool inside =
          st.x[i] >= 0.0 && st.x[i] <= W && st.y[i] >= 0.0 && (!scene.box.lid || st.y[i] <= H);
      if (!inside || !std::isfinite(st.x[i]) || !std::isfinite(st.y[i])) {
        std::ostringstream m;
        m << "the saved state's grain at " << st.where[i] << " lies at (" << st.x[i] << ", "
          << st.y[i] << ") m, outside the box [0, " << W << "] x [0, "
          << (scene.box.lid ? std::to_string(H) : std::string("inf)")) << (scene.box.lid ? "]" : "")
          << " m (box.width, box.height" << (scene.box.lid ? ", box.lid" : "") << ")";
        throw InputError(where, kKey, m.str());
      }
    }
  }
  for (std::size_t i = 0; i < st.size(); ++i)
    for (double v : {st.th[i], st.vx[i], st.vy[i], st.omega[i]})
      if (!std::isfinite(v))
        throw InputError(where, kKey,
                         "the saved state's grain at " + st.where[i] + " has a non-finite value");
  scene.resolved = scene_resolved(scene);
}

void place_saved_state(World& w, const SavedState& st) {
  for (std::size_t i = 0; i < st.size(); ++i) {
    int k = 0;
    while (w.species[static_cast<std::size_t>(k)].name != st.species[i]) ++k;
    w.add_particle(k, {st.x[i], st.y[i]}, st.th[i], {st.vx[i], st.vy[i]}, st.omega[i]);
  }
  if (!st.checkpoint) return;
  // slots keep the checkpoint's labels and periodic wrap counts
  const Checkpoint& c = *st.checkpoint;
  w.id.assign(c.id.begin(), c.id.end());
  w.s.wrap_x = c.s.wrap_x;
  w.s.wrap_y = c.s.wrap_y;
}

bool take_saved_history(Simulation& sim, const SavedState& st) {
  if (!st.checkpoint) return false;
  const Checkpoint& c = *st.checkpoint;
  const SimSettings& now = sim.settings();
  const SceneSpec& then = *st.embedded;
  if (c.integrator != static_cast<std::uint8_t>(now.integrator) ||
      then.integrator.kind != now.integrator || then.integrator.dt != now.dt ||
      then.model.kind != sim.world().model)
    return false;
  // as in restore_simulation; a fork starts its own count of degenerate contacts
  load_checkpoint_history(sim, c, false);
  return true;
}

}  // namespace gs

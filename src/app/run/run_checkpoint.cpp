// checkpoint files of a run directory: what goes into the extras, rotation, choosing the
// newest valid one, and truncating outputs back to the checkpoint
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>

#include "app/run/run_session.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"

namespace fs = std::filesystem;

namespace gs {
namespace {

constexpr const char* kPrefix = "checkpoint-";
constexpr const char* kSuffix = ".gsck";

bool is_checkpoint_name(const std::string& n) {
  return n.rfind(kPrefix, 0) == 0 && n.size() > 16 && n.compare(n.size() - 5, 5, kSuffix) == 0;
}

// files that are not appended to: rewritten whole (run.json and every JSON sidecar, state.csv,
// scene.toml, the final picture), the writer's lock (it holds the PID), checkpoints and
// temporaries, and HDF5 files (their writer keeps its frame count in the checkpoint). Their
// sizes say nothing about lost rows, and a resume must neither check nor truncate them.
bool not_appended(const std::string& n) {
  return is_checkpoint_name(n) || n == "run.json" || n == "state.csv" || n == "scene.toml" ||
         n == "final.png" || n == ".lock" ||
         (n.size() >= 5 && n.compare(n.size() - 5, 5, ".json") == 0) ||
         (n.size() >= 5 && n.compare(n.size() - 5, 5, ".h5md") == 0) ||
         (n.size() >= 4 && n.compare(n.size() - 4, 4, ".tmp") == 0);
}

// files the run appends to and their sizes: everything in DIR but the files above
std::vector<std::pair<std::string, std::uintmax_t>> output_sizes(const std::string& dir) {
  std::vector<std::pair<std::string, std::uintmax_t>> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_regular_file(ec)) continue;
    const std::string n = e.path().filename().string();
    if (not_appended(n)) continue;
    out.emplace_back(n, e.file_size(ec));
  }
  return out;
}

}  // namespace

std::string checkpoint_path(const std::string& dir, std::int64_t step) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%s%012lld%s", kPrefix, static_cast<long long>(step), kSuffix);
  return (fs::path(dir) / buf).string();
}

std::vector<std::string> list_checkpoints(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (is_checkpoint_name(e.path().filename().string())) names.push_back(e.path().string());
  // zero-padded steps: the name order is the step order
  std::sort(names.rbegin(), names.rend());
  return names;
}

double run_cpu_seconds(const RunSession& rs) {
  return rs.cpu_before + process_cpu_seconds() - rs.cpu_start;
}

void write_run_checkpoint(const RunSession& rs, double wall) {
  CheckpointExtras ex;
  ByteWriter clock;
  rs.clock->save(clock);
  ex.entries["run/clock"] = clock.out;
  ByteWriter run;
  run.f64(wall);
  run.f64(rs.wall_settled);
  run.i64(rs.sessions);
  const auto [ref, slack] = rs.sim->energy_yardstick();
  run.f64(ref);
  run.f64(slack);
  ex.entries["run/session"] = run.out;
  ByteWriter cpu;
  cpu.f64(run_cpu_seconds(rs));
  cpu.i64(rs.cpu_sessions);
  ex.entries["run/cpu"] = cpu.out;
  ex.entries["run/scene_file"] = rs.scene_file;
  for (const auto& o : rs.observers) {
    ByteWriter w;
    o->save(w);
    ex.entries[std::string("observer/") + o->name()] = w.out;
  }
  // every output is flushed row by row, so the sizes on disk are the rows written so far
  for (const auto& [name, size] : output_sizes(rs.out))
    ex.entries["file/" + name] = std::to_string(size);
  const std::string path = checkpoint_path(rs.out, rs.sim->world().s.step);
  write_checkpoint(*rs.sim, rs.scene, ex, path);
  // keep the newest two
  const auto all = list_checkpoints(rs.out);
  std::error_code ec;
  for (std::size_t k = 2; k < all.size(); ++k) fs::remove(all[k], ec);
}

Checkpoint newest_valid_checkpoint(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) throw InputError(dir, "", "run directory does not exist");
  if (!fs::is_directory(dir, ec)) throw InputError(dir, "", "is not a run directory");
  const auto all = list_checkpoints(dir);
  if (all.empty())
    throw InputError(dir, "",
                     "no checkpoint (checkpoint-*.gsck) in this directory; a run writes them on "
                     "its output.checkpoint_steps, _taps and _minutes schedule and when it is "
                     "stopped");
  std::string why;
  for (const std::string& p : all) {
    try {
      Checkpoint c = read_checkpoint(p);
      for (const auto& [key, value] : c.extras.entries) {
        // (checkpoints written before a file was known not to be appended may list it)
        if (key.rfind("file/", 0) != 0 || not_appended(key.substr(5))) continue;
        const fs::path f = fs::path(dir) / key.substr(5);
        const std::uintmax_t want = std::stoull(value);
        if (!fs::exists(f, ec) || fs::file_size(f, ec) < want)
          throw InputError(f.string(), "",
                           "shorter than when " + p + " was written (" + value +
                               " bytes); rows after it would be lost");
      }
      return c;
    } catch (const InputError& e) {
      std::fprintf(stderr, "gransim: skipping %s: %s\n", p.c_str(), e.what());
      why = e.what();
    } catch (const std::exception& e) {  // stoull on a damaged size
      std::fprintf(stderr, "gransim: skipping %s: %s\n", p.c_str(), e.what());
      why = e.what();
    }
  }
  throw InputError(dir, "", "no valid checkpoint (last problem: " + why + ")");
}

void truncate_outputs(const std::string& dir, const Checkpoint& c) {
  for (const auto& [key, value] : c.extras.entries) {
    if (key.rfind("file/", 0) != 0 || not_appended(key.substr(5))) continue;
    const fs::path f = fs::path(dir) / key.substr(5);
    std::error_code ec;
    fs::resize_file(f, std::stoull(value), ec);
    if (ec) throw InputError(f.string(), "", "cannot truncate to the checkpoint: " + ec.message());
  }
}

}  // namespace gs

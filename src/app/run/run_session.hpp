// the run loop shared by `gransim run` and `gransim resume`: step, observe, write the series,
// checkpoint on the scene's schedule and when stopped, then run.json (app/run/run_loop.cpp);
// checkpoint files of a run directory (app/run/run_checkpoint.cpp)
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "app/openmp_team.hpp"
#include "drive/protocol.hpp"
#include "output/csv.hpp"
#include "output/run_dir.hpp"
#include "scene/spec.hpp"
#include "sim/checkpoint.hpp"
#include "sim/observer.hpp"
#include "sim/simulation.hpp"

namespace gs {

struct RunSession {
  SceneSpec scene;         ///< the run's scene (overrides applied)
  std::string scene_file;  ///< the file it came from, for run.json
  std::string out;         ///< run directory
  bool quiet = false;
  bool profile = false;    ///< print the step's profile at the end (gransim run --profile)
  double step_loop = 0.0;  ///< wall time inside Simulation::run this session, s
  Simulation* sim = nullptr;
  ProtocolClock* clock = nullptr;
  Observers observers;         ///< started or resumed
  CsvWriter series;            ///< series.csv, open
  double wall_before = 0.0;    ///< wall time of earlier sessions of this run, s
  double wall_settled = -1.0;  ///< wall time when settling ended (−1: not yet), s
  int sessions = 1;            ///< 1 + number of resumes
  /// CPU time of the earlier sessions whose checkpoints kept it, and how many of the sessions,
  /// this one included, cpu_before + this session's CPU time covers (sessions when all)
  double cpu_before = 0.0;
  int cpu_sessions = 1;
  double cpu_start = 0.0;           ///< process_cpu_seconds() when this session began
  OpenMpTeam team = openmp_team();  ///< the threads and CPUs this session runs on
  /// a replaced run's files (run --force), discarded once the first health check has passed
  SetAside* replaced = nullptr;
};

/// the series.csv columns
std::vector<std::string> series_columns();

/// one series.csv row of the current state
void write_series_row(RunSession& rs);

/// step until done or stopped; returns the exit code (kExitOk, kExitUnstable, kExitInterrupted,
/// kExitOutput)
int run_session(RunSession& rs);

// ---- checkpoint files (app/run/run_checkpoint.cpp) ----

/// DIR/checkpoint-<step, 12 digits>.gsck
std::string checkpoint_path(const std::string& dir, std::int64_t step);
/// the run's checkpoints, newest first
std::vector<std::string> list_checkpoints(const std::string& dir);
/// write a checkpoint of the session (files flushed, sizes recorded) and keep the newest two
/// `wall` is the run's wall time so far (all sessions), s
void write_run_checkpoint(const RunSession& rs, double wall);
/// the run's CPU time so far: cpu_before and this session's, s
double run_cpu_seconds(const RunSession& rs);
/// the newest checkpoint of DIR that reads back cleanly and whose recorded files are all
/// still there and long enough; InputError naming DIR when there is none
Checkpoint newest_valid_checkpoint(const std::string& dir);
/// truncate every file recorded in the checkpoint to its recorded size
void truncate_outputs(const std::string& dir, const Checkpoint& c);

}  // namespace gs

// the parts of `gransim sweep` shared by the serial driver (sweep.cpp) and the MPI driver
// (sweep_mpi.cpp): the plan (every run, validated up front), starting one run as a child
// process, the manifest, and rank 0's bookkeeping of which run is where
#pragma once
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "app/sweep/sweep.hpp"

namespace gs::sweep_detail {

/// one run as the sweep tracks it
struct Job {
  SweepRun run;
  int replica = 0;                ///< 0: the seed of the scene; r > 0: a derived seed
  std::string dir;                ///< OUT/<name>
  double nominal = 0.0;           ///< simulated time it needs, s
  double work = 1.0;              ///< particle-steps per simulated second: its progress' weight
  std::string expected;           ///< the scene.toml the run writes (scene_to_toml)
  std::string state = "pending";  ///< pending, skipped, running, completed, interrupted, failed
  bool resume = false;            ///< an interrupted run with a checkpoint: `gransim resume` it
  int exit_code = -1;
  pid_t pid = -1;  ///< a child of this process (-1: none, or on another rank)
  int rank = 0;    ///< MPI rank that runs it
  std::chrono::steady_clock::time_point started;
  std::filesystem::file_time_type spawned;  ///< for telling its own series.csv from an older one
  double wall = 0.0;                        ///< s
};

/// a validated sweep: what every rank computes the same way from the same arguments
struct SweepPlan {
  SweepOptions opt;
  std::vector<SweepParam> params;
  std::string base_hash;  ///< FNV-1a of the resolved base scene
  std::string out;        ///< sweep directory
  std::vector<Job> jobs;  ///< replica 0 of every value first, then replica 1, …
};

/// parse the parameters and every run's scene (throws InputError naming the argument); with
/// `check_dirs` also create OUT/logs and mark completed runs skipped, refusing a directory of
/// another sweep and unfinished runs without --force (only rank 0 does this under MPI)
SweepPlan plan_sweep(const SweepOptions& opt, bool check_dirs);

/// the seed of replica r > 0 of a run whose scene seed is `base`
std::uint64_t replica_seed(std::uint64_t base, int replica);

/// the children's environment: ours without MPI's variables, plus OMP_NUM_THREADS = `threads`
/// unless it is set already
std::vector<std::string> child_environment(int threads);

/// start `gransim run` for a job, output to OUT/logs/<name>.log
pid_t spawn_run(const SweepPlan& plan, const Job& j, const std::vector<std::string>& env);

/// the exit code of a finished child from its waitpid status
int child_exit_code(int status);

/// the simulated time of a run's last series.csv row (0 when none, or older than `since`)
double last_series_time(const std::string& dir, std::filesystem::file_time_type since);

/// OUT/sweep.json: scene, parameters and every run with its state
void write_manifest(const SweepPlan& plan, bool finished);

/// the worse of two exit codes (interrupted > unstable > failure > ok)
int worse_exit(int a, int b);

/// a peer that runs some of the jobs elsewhere (the MPI worker ranks); rank 0's loop asks it
/// to answer its messages each turn
class RemoteSlots {
 public:
  virtual ~RemoteSlots() = default;
  /// take the workers' messages: report finished runs through `done(index, exit, wall)` and
  /// hand each free slot `next()` (a job index, or -1 to close the slot)
  virtual void poll(const std::function<void(int, int, double)>& done,
                    const std::function<int(int rank)>& next) = 0;
  /// slots that are still open (running a job or waiting for one)
  virtual int open() const = 0;
};

/// started by mpirun or srun with more than one task (OMPI_COMM_WORLD_SIZE, PMI_SIZE, PMIX_RANK,
/// SLURM_NTASKS > 1); GS_SWEEP_NO_MPI=1 ignores it
bool mpi_launch_detected();

/// the sweep over MPI ranks: rank 0 validates, keeps the manifest and hands out runs, every
/// rank runs them; returns the same exit code on every rank (sweep_mpi.cpp)
int sweep_mpi(const SweepOptions& opt);

/// rank 0 (or the only process): run every pending job, `width` at a time here, the rest on
/// `remote` when given; one progress display; returns the worst exit code
int run_jobs(SweepPlan& plan, int width, int threads, RemoteSlots* remote);
/// the same over several sweeps' plans as one pool of runs (no `remote` with more than one)
int run_jobs(const std::vector<SweepPlan*>& plans, int width, int threads, RemoteSlots* remote);

}  // namespace gs::sweep_detail

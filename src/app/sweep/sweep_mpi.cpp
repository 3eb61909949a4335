// `mpirun -np K gransim sweep …`: the runs of one sweep spread over MPI ranks (and nodes).
// Every rank computes the same plan from the same arguments; rank 0 alone checks the sweep
// directory (completed runs are skipped, as in a serial sweep), keeps OUT/sweep.json and hands
// out run indices one at a time to whichever rank has a free slot, so uneven runs balance.
// A rank runs a run exactly as a serial sweep does, as a child `gransim run` process, so the
// output is byte for byte that of a serial sweep. Rank 0 runs its share too.
//
// Messages: worker → 0 (tag kRequest): {index of a finished run or -1, its exit code (-1: not
// started), its wall time}, which also asks for the next run; 0 → worker (tag kAssign): a run
// index, or -1 (no more: that slot closes). A worker ends when all its slots are closed.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <thread>

#include "app/run/run.hpp"
#include "app/sweep/sweep_detail.hpp"
#include "core/error.hpp"
#include "output/run_dir.hpp"

#ifdef GS_HAVE_MPI
#include <mpi.h>
#endif

namespace gs::sweep_detail {

namespace {

long env_long(const char* name) {
  const char* v = std::getenv(name);
  return v && *v ? std::strtol(v, nullptr, 10) : -1;
}

}  // namespace

bool mpi_launch_detected() {
  if (const char* no = std::getenv("GS_SWEEP_NO_MPI"); no && *no && std::strcmp(no, "0") != 0)
    return false;
  // Open MPI's mpirun, MPICH/Intel hydra and Slurm's PMI2, PMIx (srun --mpi=pmix, Open MPI 5)
  const bool launched = env_long("OMPI_COMM_WORLD_SIZE") > 1 || env_long("PMI_SIZE") > 1 ||
                        std::getenv("PMIX_RANK") != nullptr;
  if (launched) return true;
  // srun without an MPI plugin starts K independent copies that would all run the whole sweep
  // into the same directory: refuse on every task but the first
  if (env_long("SLURM_STEP_NUM_TASKS") > 1 && env_long("SLURM_PROCID") > 0)
    throw InputError("", "",
                     "started by srun as task " + std::to_string(env_long("SLURM_PROCID")) +
                         " without MPI (no PMI/PMIx variables): launch with srun --mpi=pmix "
                         "(or pmi2), or mpirun, or use a single task");
  return false;
}

#ifndef GS_HAVE_MPI

int sweep_mpi(const SweepOptions&) {
  throw InputError("", "",
                   "started under mpirun/srun with several ranks, but this gransim was built "
                   "without MPI (install libopenmpi-dev and rebuild), or set GS_SWEEP_NO_MPI=1 "
                   "and start a single process");
}

#else

namespace {

constexpr int kRequest = 1, kAssign = 2;

// rank 0's view of the worker ranks: one open slot per run a worker may run at a time
class MpiWorkers : public RemoteSlots {
 public:
  MpiWorkers(int size, int width) : open_((size - 1) * width) {}
  void poll(const std::function<void(int, int, double)>& done,
            const std::function<int(int)>& next) override {
    for (;;) {
      int flag = 0;
      MPI_Status st;
      MPI_Iprobe(MPI_ANY_SOURCE, kRequest, MPI_COMM_WORLD, &flag, &st);
      if (!flag) return;
      double msg[3];
      MPI_Recv(msg, 3, MPI_DOUBLE, st.MPI_SOURCE, kRequest, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (msg[0] >= 0) done(static_cast<int>(msg[0]), static_cast<int>(msg[1]), msg[2]);
      // a run refused by a stopping worker goes back to the queue and closes that slot
      int index = msg[0] >= 0 && msg[1] < 0 ? -1 : next(st.MPI_SOURCE);
      MPI_Send(&index, 1, MPI_INT, st.MPI_SOURCE, kAssign, MPI_COMM_WORLD);
      if (index < 0) --open_;
    }
  }
  int open() const override { return open_; }

 private:
  int open_;
};

// a worker rank: ask for runs for `width` slots, run each as a child process, report back
void worker_loop(const SweepPlan& plan, int width, int threads) {
  std::vector<std::string> env = child_environment(threads);
  install_stop_handlers();
  struct Slot {
    int index = -1;
    pid_t pid = -1;
    std::chrono::steady_clock::time_point started;
  };
  std::vector<Slot> running;
  int outstanding = 0;
  auto request = [&](double index, double code, double wall) {
    double msg[3] = {index, code, wall};
    MPI_Send(msg, 3, MPI_DOUBLE, 0, kRequest, MPI_COMM_WORLD);
    ++outstanding;
  };
  for (int k = 0; k < width; ++k) request(-1, 0, 0);
  bool stopping = false;
  while (outstanding > 0 || !running.empty()) {
    if (stop_requested() && !stopping) {
      stopping = true;
      for (const Slot& s : running) kill(s.pid, SIGTERM);
    }
    bool busy = false;
    for (;;) {  // answers from rank 0
      int flag = 0;
      MPI_Iprobe(0, kAssign, MPI_COMM_WORLD, &flag, MPI_STATUS_IGNORE);
      if (!flag) break;
      int index = -1;
      MPI_Recv(&index, 1, MPI_INT, 0, kAssign, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      --outstanding;
      busy = true;
      if (index < 0 || index >= static_cast<int>(plan.jobs.size())) continue;  // slot closed
      if (stopping) {
        request(index, -1, 0);  // not started: rank 0 puts it back
        continue;
      }
      Slot s;
      s.index = index;
      s.started = std::chrono::steady_clock::now();
      s.pid = spawn_run(plan, plan.jobs[static_cast<std::size_t>(index)], env);
      running.push_back(s);
    }
    for (std::size_t k = 0; k < running.size();) {  // finished children
      int status = 0;
      if (waitpid(running[k].pid, &status, WNOHANG) != running[k].pid) {
        ++k;
        continue;
      }
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - running[k].started)
              .count();
      request(running[k].index, child_exit_code(status), wall);
      running.erase(running.begin() + static_cast<long>(k));
      busy = true;
    }
    if (!busy) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// MPI_Init … MPI_Finalize around the sweep, whichever way it ends
struct MpiSession {
  MpiSession() { MPI_Init(nullptr, nullptr); }
  ~MpiSession() { MPI_Finalize(); }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

}  // namespace

int sweep_mpi(const SweepOptions& opt) {
  MpiSession mpi;
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  // ranks on this node, for OMP_NUM_THREADS of the children (cores / runs at a time here)
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node);
  int local = 1;
  MPI_Comm_size(node, &local);
  MPI_Comm_free(&node);

  // the plan on every rank; the checks of the sweep directory on rank 0. Bad input anywhere:
  // exit 2 on every rank and nothing is started (rank 0 names the problem, or the rank that saw it)
  SweepPlan plan;
  std::string error;
  int code = kExitOk;
  // rank 0 holds the sweep directory's lock, as a serial sweep does; each run's child process
  // locks its own run directory
  std::optional<DirLock> lock;
  try {
    if (rank == 0) lock.emplace(plan_sweep(opt, false).out, "sweep");
    plan = plan_sweep(opt, rank == 0);
  } catch (const InputError& e) {
    error = e.what();
    code = kExitBadInput;
  } catch (const std::exception& e) {
    error = std::string("internal error: ") + e.what();
    code = kExitFailure;
  }
  // every rank must see the same scene (a file missing or different on another node)
  char hash[17] = {};
  std::snprintf(hash, sizeof hash, "%s", plan.base_hash.c_str());
  MPI_Bcast(hash, sizeof hash, MPI_CHAR, 0, MPI_COMM_WORLD);
  if (code == kExitOk && plan.base_hash != hash) {
    error = "the scene differs from rank 0's (base scene hash " + plan.base_hash + ", rank 0 " +
            hash + "): is " + opt.scene + " the same file on every node?";
    code = kExitBadInput;
  }
  int code0 = code, worst = code;
  MPI_Bcast(&code0, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (worst != kExitOk) {
    if (code != kExitOk && (rank == 0 || code0 == kExitOk))
      std::fprintf(stderr, "gransim: error%s: %s\n",
                   rank == 0 ? "" : (" (rank " + std::to_string(rank) + ")").c_str(),
                   error.c_str());
    return worst == kExitFailure ? kExitFailure : kExitBadInput;
  }

  // one run at a time per rank unless --jobs says more; the children share the node's cores
  const int width = std::max(1, opt.jobs);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::max(1, cores / (width * local));
  int result = kExitOk;
  try {
    if (rank == 0) {
      MpiWorkers workers(size, width);
      result = run_jobs(plan, width, threads, &workers);
    } else {
      worker_loop(plan, width, threads);
    }
  } catch (const std::exception& e) {
    // a run that cannot be started: nothing sensible is left for the other ranks
    std::fprintf(stderr, "gransim: internal error (rank %d): %s\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, kExitFailure);
  }
  MPI_Bcast(&result, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return result;
}

#endif

}  // namespace gs::sweep_detail

// gransim's entry point
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "app/cli.hpp"
#include "app/openmp_team.hpp"

namespace {

// libgomp reads its wait policy when it is loaded, before main. Its default lets a waiting
// thread spin for ~300 000 rounds and then sleep; on virtual machines the wake-up that follows
// costs so much that two threads can run a paper tap slower than one (docs/threads.md). Unless
// the user chose a policy or a spin count (or runs one thread), start again once with a longer
// spin: a waiting thread still sleeps after ~10⁷ rounds, so an idle team does not burn a core
// for long.
void ensure_spin_count(char** argv) {
  // set and not empty (libgomp ignores an empty value as it ignores a missing one)
  auto given = [](const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0';
  };
  if (given("OMP_WAIT_POLICY") || given("GOMP_SPINCOUNT")) return;
  const char* threads = std::getenv("OMP_NUM_THREADS");
  if (threads && std::strcmp(threads, "1") == 0) return;
  if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return;
  if (setenv("GOMP_SPINCOUNT", "10000000", 1) != 0) return;
  // with OMP_PROC_BIND the runtime has bound this thread to one CPU already; the new process
  // would inherit that mask and bind all its threads to that CPU: give it back every CPU of the
  // places first
  gs::widen_to_places();
  execv("/proc/self/exe", argv);  // returns only on failure: carry on as we are
}

}  // namespace

int main(int argc, char** argv) {
  ensure_spin_count(argv);
  return gs::run_cli(argc, argv);
}

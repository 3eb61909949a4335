// gransim's entry point
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "app/cli.hpp"

namespace {

// libgomp reads its wait policy when it initialises. Its default lets a waiting thread spin for
// ~300 000 rounds and then sleep; on virtual machines the wake-up that follows costs so much
// that two threads can run a paper tap slower than one (docs/threads.md). Unless the user chose
// a policy or a spin count (or runs one thread), ask for a longer spin: a waiting thread still
// sleeps after ~10⁷ rounds, so an idle team does not burn a core for long. The executable links
// the runtime statically (CMakeLists.txt), so this constructor, of the highest priority, runs
// before the runtime's own: the choice is made once, in this process, without a restart.
[[gnu::constructor(101)]] void choose_spin_count() {
  // set and not empty (libgomp ignores an empty value as it ignores a missing one)
  auto given = [](const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != '\0';
  };
  if (given("OMP_WAIT_POLICY") || given("GOMP_SPINCOUNT")) return;
  const char* threads = std::getenv("OMP_NUM_THREADS");
  if (threads && std::strcmp(threads, "1") == 0) return;
  if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return;
  setenv("GOMP_SPINCOUNT", "10000000", 1);
}

}  // namespace

int main(int argc, char** argv) { return gs::run_cli(argc, argv); }

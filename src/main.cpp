// gransim's entry point
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "app/cli.hpp"

namespace {

// libgomp reads its wait policy when it is loaded, before main. Its default lets a waiting
// thread spin for ~300 000 rounds and then sleep; on virtual machines the wake-up that follows
// costs so much that a 2-thread paper tap ran at 0.9–1.4·10⁶ particle-steps/s against 2.9·10⁶
// on one thread (4.0–4.1·10⁶ with a longer spin, docs/speed-accuracy.md). Unless the user chose
// a policy or a spin count (or runs one thread), start again once with a longer spin: a waiting
// thread still sleeps after ~10⁷ rounds, so an idle team does not burn a core for long.
void ensure_spin_count(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  const char* threads = std::getenv("OMP_NUM_THREADS");
  if (threads && std::strcmp(threads, "1") == 0) return;
  if (sysconf(_SC_NPROCESSORS_ONLN) < 2) return;
  if (setenv("GOMP_SPINCOUNT", "10000000", 1) != 0) return;
  execv("/proc/self/exe", argv);  // returns only on failure: carry on as we are
}

}  // namespace

int main(int argc, char** argv) {
  ensure_spin_count(argv);
  return gs::run_cli(argc, argv);
}

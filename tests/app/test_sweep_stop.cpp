// a sweep's runs end with the sweep, however it ends: killed with SIGKILL (no chance to pass
// the signal on), its runs still stop within seconds, each with a checkpoint to resume from
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::Launch;
using testing::run_binary;

// does some process hold DIR/.lock (a run still writing there)?
bool locked(const fs::path& dir) {
  const int fd = ::open((dir / ".lock").c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return false;
  const bool held = ::flock(fd, LOCK_EX | LOCK_NB) != 0;
  ::close(fd);
  return held;
}

bool has_checkpoint(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".gsck") return true;
  return false;
}

TEST(SweepStop, RunsStopWithAKilledSweepAndCanResume) {
  const fs::path tmp = testing::fresh_test_dir("gs_sweep_stop");
  std::ofstream(tmp / "tiny.toml") << testing::tiny_tapping_scene(2000);
  const fs::path out = tmp / "sweep";
  const fs::path runs[] = {out / "g_p=2", out / "g_p=4"};
  Launch kill;
  kill.alarm_s = 300;
  kill.signal = SIGKILL;
  // killed once both runs are under way (each has checkpointed once)
  kill.signal_when = [&] { return has_checkpoint(runs[0]) && has_checkpoint(runs[1]); };
  const auto sweep =
      run_binary({"sweep", (tmp / "tiny.toml").string(), "--param", "drive.g_p=2,4", "--jobs", "2",
                  "-q", "--set", "output.checkpoint_steps=2000", "--out", out.string()},
                 tmp / "sweep.log", kill);
  ASSERT_FALSE(sweep.exited) << "the sweep ended before it was killed\n" << sweep.output;
  // the runs notice and stop on their own (a run of 2000 taps would take many minutes)
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while ((locked(runs[0]) || locked(runs[1])) && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  for (const fs::path& r : runs) {
    EXPECT_FALSE(locked(r)) << r << ": its run outlived the sweep";
    EXPECT_TRUE(has_checkpoint(r)) << r;
    const std::string log = testing::slurp(out / "logs" / (r.filename().string() + ".log"));
    EXPECT_NE(log.find("resume"), std::string::npos) << r << " did not stop cleanly:\n" << log;
  }
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs

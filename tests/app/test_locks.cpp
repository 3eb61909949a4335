// one writer per run directory: a second run, resume or sweep into a directory another gransim
// process is writing is refused (exit 2, naming the holder's PID); kill -9 leaves no stale lock;
// an analysis never writes into a run or one of its inputs
#include <gtest/gtest.h>
#include <signal.h>

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

const std::string kDemo = std::string(GS_SOURCE_DIR) + "/scenes/demo.toml";

fs::path fresh(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("gs-locks-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// the PID a running writer put into DIR/.lock, once it has (0 when it never does)
long holder(const fs::path& dir, double timeout_s) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < until) {
    std::ifstream in(dir / ".lock");
    long pid = 0;
    if (in >> pid && pid > 0 && fs::exists(dir / "series.csv")) return pid;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return 0;
}

TEST(RunDirLock, SecondWriterIsRefusedAndKillLeavesNoStaleLock) {
  const fs::path tmp = fresh("run");
  const fs::path dir = tmp / "run";
  // a long run in the background: the first writer
  testing::Outcome first;
  Launch slow;
  slow.alarm_s = 120;
  std::thread t([&] {
    first = run_binary({"run", kDemo, "--out", dir.string(), "--set", "scene.duration=600", "-q"},
                       tmp / "first.log", slow);
  });
  const long pid = holder(dir, 60.0);
  ASSERT_GT(pid, 0) << "the first run never took its lock";

  // a second run with --force, a resume and a sweep into it are refused while it runs
  const auto second =
      run_binary({"run", kDemo, "--out", dir.string(), "--force", "-q"}, tmp / "second.log");
  EXPECT_TRUE(second.exited);
  EXPECT_EQ(second.code, 2) << second.output;
  EXPECT_NE(second.output.find("PID " + std::to_string(pid)), std::string::npos) << second.output;
  EXPECT_NE(second.output.find(dir.string()), std::string::npos) << second.output;
  const auto resume = run_binary({"resume", dir.string(), "-q"}, tmp / "resume.log");
  EXPECT_EQ(resume.code, 2) << resume.output;
  // the first run's files are untouched: its series keeps growing
  EXPECT_TRUE(fs::exists(dir / "series.csv"));
  EXPECT_TRUE(fs::exists(dir / "scene.toml"));

  // kill -9: the kernel drops the lock with the process; the next writer gets in
  ::kill(static_cast<pid_t>(pid), SIGKILL);
  t.join();
  EXPECT_FALSE(first.exited);
  const auto after = run_binary(
      {"run", kDemo, "--out", dir.string(), "--force", "-q", "--set", "scene.duration=0.02"},
      tmp / "after.log");
  EXPECT_EQ(after.code, 0) << after.output;
  fs::remove_all(tmp);
}

TEST(RunDirLock, AnalysisNeverWritesIntoARunOrAnInput) {
  const fs::path tmp = fresh("analyze");
  const fs::path run = tmp / "tap";
  Launch slow;
  slow.alarm_s = 120;
  const auto r =
      run_binary({"run", std::string(GS_SOURCE_DIR) + "/scenes/tap_small_negative_g.toml", "--out",
                  run.string(), "-q", "--set", "drive.taps=2"},
                 tmp / "run.log", slow);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto before = fs::last_write_time(run / "series.csv");
  for (const fs::path& out : {run, run / ".", tmp / "tap"}) {
    const auto a = run_binary({"analyze", run.string(), "--out", out.string(), "--no-charts"},
                              tmp / "analyze.log");
    EXPECT_EQ(a.code, 2) << a.output;
    EXPECT_NE(a.output.find("choose another --out"), std::string::npos) << a.output;
  }
  EXPECT_EQ(fs::last_write_time(run / "series.csv"), before);
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs

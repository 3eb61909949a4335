// the OpenMP team of a run, as run.json reports it: with thread binding asked for
// (OMP_PROC_BIND, as tools/slurm_sweep.sh sets it) each thread runs on a CPU of its own; and the
// runtime starts once, with the wait policy its environment gives
#include <gtest/gtest.h>
#include <sched.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// the integer value of "key" in a run.json (−1 when missing)
long json_int(const fs::path& file, const std::string& key) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  std::smatch m;
  const std::string text = s.str();
  if (!std::regex_search(text, m, std::regex("\"" + key + "\": (-?[0-9]+)"))) return -1;
  return std::stol(m[1].str());
}

// CPUs this test process may run on
int allowed_cpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0) return 1;
  return CPU_COUNT(&set);
}

class Threads : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::fresh_test_dir("gs_threads"); }
  void TearDown() override { fs::remove_all(dir_); }

  // a short run of the demo pile with this environment; run.json's path
  fs::path run(const std::vector<std::string>& env) {
    testing::Launch how;
    how.env = env;
    how.alarm_s = 120;
    const fs::path out = dir_ / "run";
    const testing::Outcome o = testing::run_binary(
        {"run", std::string(GS_SOURCE_DIR) + "/scenes/demo.toml", "--out", out.string(), "--force",
         "--quiet", "--set", "preparation.settle_time=0.02"},
        dir_ / "log.txt", how);
    EXPECT_TRUE(o.exited && o.code == 0) << o.output;
    return out / "run.json";
  }
  fs::path dir_;
};

TEST_F(Threads, RunJsonReportsTheTeam) {
  const fs::path js = run({"OMP_NUM_THREADS=1"});
  EXPECT_EQ(json_int(js, "omp_threads"), 1);
  // one thread, not bound: it may run on every CPU this test may
  EXPECT_EQ(json_int(js, "omp_cpus"), allowed_cpus());
}

// two threads with binding on: two CPUs (the failure guarded against: both threads bound to the
// first one, which leaves a 2-thread run slower than one thread)
TEST_F(Threads, BoundThreadsKeepTheirOwnCpus) {
  if (allowed_cpus() < 2) GTEST_SKIP() << "this machine gives the test one CPU";
  for (const char* bind : {"OMP_PROC_BIND=true", "OMP_PROC_BIND=close"}) {
    const fs::path js = run({"OMP_NUM_THREADS=2", bind, "GOMP_SPINCOUNT=", "OMP_WAIT_POLICY="});
    EXPECT_EQ(json_int(js, "omp_threads"), 2) << bind;
    EXPECT_EQ(json_int(js, "omp_cpus"), 2) << bind;
  }
  const fs::path js = run({"OMP_NUM_THREADS=2", "OMP_PROC_BIND=false"});
  EXPECT_EQ(json_int(js, "omp_cpus"), 2);
}

// the runtime starts once (OMP_DISPLAY_ENV prints its settings at each start of a process):
// gransim never re-executes itself to change its wait policy; a run of several threads without
// a chosen policy says how to choose one, and a chosen one is what the runtime uses
TEST_F(Threads, OneStartAndTheWaitPolicyAsTheUserChoseIt) {
  auto run_with = [&](const std::vector<std::string>& env) {
    testing::Launch how;
    how.env = env;
    how.env.push_back("OMP_DISPLAY_ENV=verbose");
    how.alarm_s = 120;
    const testing::Outcome o = testing::run_binary(
        {"run", std::string(GS_SOURCE_DIR) + "/scenes/demo.toml", "--out", (dir_ / "w").string(),
         "--force", "--quiet", "--set", "preparation.settle_time=0.02"},
        dir_ / "display.txt", how);
    EXPECT_TRUE(o.exited && o.code == 0) << o.output;
    return o.output;
  };
  auto count = [](const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
      ++n;
    return n;
  };
  const std::string plain = run_with({"OMP_NUM_THREADS=2", "GOMP_SPINCOUNT=", "OMP_WAIT_POLICY="});
  EXPECT_EQ(count(plain, "OPENMP DISPLAY ENVIRONMENT BEGIN"), 1u) << plain;
  EXPECT_NE(plain.find("start gransim with GOMP_SPINCOUNT=10000000"), std::string::npos) << plain;
  const std::string chosen = run_with({"OMP_NUM_THREADS=2", "GOMP_SPINCOUNT=4321"});
  EXPECT_EQ(count(chosen, "OPENMP DISPLAY ENVIRONMENT BEGIN"), 1u) << chosen;
  EXPECT_NE(chosen.find("GOMP_SPINCOUNT = '4321'"), std::string::npos) << chosen;
  EXPECT_EQ(chosen.find("start gransim with"), std::string::npos) << chosen;
  const std::string one = run_with({"OMP_NUM_THREADS=1", "GOMP_SPINCOUNT=", "OMP_WAIT_POLICY="});
  EXPECT_EQ(one.find("start gransim with"), std::string::npos) << one;
}

}  // namespace
}  // namespace gs

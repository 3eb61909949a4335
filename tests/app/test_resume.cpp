// kill and resume: a run killed with SIGKILL at random moments and continued with
// `gransim resume` ends with the same files, byte for byte, as the run that was never
// interrupted — the final state, every per-tap, series and RFM row — for a polygon tapping
// scene and a disk RFM scene, with 1 and 2 threads; SIGINT writes a checkpoint and says how
// to resume; a damaged newest checkpoint falls back to the one before
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::Launch;
using testing::Outcome;
using testing::run_binary;
using testing::slurp;

const std::string kSource = GS_SOURCE_DIR;

// every output file of a run directory except run.json (wall times), the checkpoints and the
// writer's lock (it holds the writer's PID)
std::map<std::string, std::string> outputs(const fs::path& dir) {
  std::map<std::string, std::string> m;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string name = fs::relative(e.path(), dir).string();
    if (name == "run.json" || name.rfind("checkpoint-", 0) == 0 || e.path().filename() == ".lock")
      continue;
    m[name] = slurp(e.path());
  }
  return m;
}

// checkpoints in a run directory
std::size_t list_size(const fs::path& dir) {
  std::size_t n = 0;
  if (fs::exists(dir))
    for (const auto& e : fs::directory_iterator(dir))
      // complete checkpoints only: a kill during a write leaves checkpoint-….gsck.tmp
      n += e.path().filename().string().rfind("checkpoint-", 0) == 0 &&
           e.path().extension() == ".gsck";
  return n;
}

struct Case {
  std::string label;
  std::vector<std::string> run_args;  ///< scene and --set overrides
  std::string threads;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.label; }

class KillResume : public ::testing::TestWithParam<Case> {};

// one folder per test process: two test suites on one machine must not share a run directory
fs::path fresh(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("gs_resume_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::vector<std::string> with_out(std::vector<std::string> a, const fs::path& out) {
  a.insert(a.begin(), "run");
  a.insert(a.end(), {"--out", out.string(), "--quiet"});
  return a;
}

// run_binary, with the run's wall time (s) in `wall`: the moments at which the tests below
// interrupt a run are fractions of it
Outcome timed_run(const std::vector<std::string>& args, const fs::path& log, double& wall,
                  const Launch& how = {}) {
  const auto t0 = std::chrono::steady_clock::now();
  Outcome o = run_binary(args, log, how);
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return o;
}

TEST_P(KillResume, SigkillAtRandomMomentsThenResumeIsBitwise) {
  const Case& c = GetParam();
  const fs::path tmp = fresh(c.label);
  Launch env;
  env.env = {"OMP_NUM_THREADS=" + c.threads};
  env.alarm_s = 120;
  // the uninterrupted reference and its wall time
  double wall = 0.0;
  const Outcome ref = timed_run(with_out(c.run_args, tmp / "ref"), tmp / "ref.log", wall, env);
  ASSERT_TRUE(ref.exited && ref.code == 0) << ref.output;
  const auto want = outputs(tmp / "ref");
  ASSERT_TRUE(want.count("series.csv") && want.count("state.csv"));
  // the quench case must exercise the quench
  if (c.label.find("quench") != std::string::npos) {
    const std::string js = slurp(tmp / "ref" / "run.json");
    EXPECT_NE(js.find("\"quench_events\": "), std::string::npos) << js;
    EXPECT_EQ(js.find("\"quench_events\": 0,"), std::string::npos) << "no quench in " << js;
  }

  // kill at random moments between 15% and 85% of the run (fixed seed: reproducible)
  std::mt19937 rng(20261121u + static_cast<unsigned>(c.threads[0]));
  std::uniform_real_distribution<double> when(0.15 * wall, 0.85 * wall);
  for (int k = 0; k < 3; ++k) {
    const fs::path dir = tmp / ("killed" + std::to_string(k));
    Launch kill = env;
    kill.signal_after_s = when(rng);
    kill.signal = SIGKILL;
    // a kill before the run's first checkpoint leaves nothing to resume, one after its end
    // kills nothing: on a loaded machine either can happen at the drawn moment, so the moment
    // moves (later, or bisected between the two) until a killed run has a checkpoint
    double too_early = 0.0, too_late = -1.0;
    Outcome killed;
    for (int attempt = 0; attempt < 10; ++attempt) {
      fs::remove_all(dir);
      killed = run_binary(with_out(c.run_args, dir), tmp / "killed.log", kill);
      if (killed.exited) {
        too_late = kill.signal_after_s;
      } else if (list_size(dir) == 0) {
        too_early = kill.signal_after_s;
      } else {
        break;
      }
      kill.signal_after_s =
          too_late > 0.0 ? 0.5 * (too_early + too_late) : kill.signal_after_s + 0.1 * wall;
    }
    ASSERT_FALSE(killed.exited) << "the run ended before the kill at " << kill.signal_after_s
                                << " s (reference took " << wall << " s)";
    ASSERT_GT(list_size(dir), 0u) << "no checkpoint before the kill at " << kill.signal_after_s
                                  << " s (reference took " << wall << " s)";
    const Outcome r = run_binary({"resume", dir.string(), "--quiet"}, tmp / "resume.log", env);
    ASSERT_TRUE(r.exited && r.code == 0) << "kill at " << kill.signal_after_s << " s\n" << r.output;
    EXPECT_NE(r.output.find("resuming"), std::string::npos) << r.output;
    const auto got = outputs(dir);
    ASSERT_EQ(got.size(), want.size()) << "kill at " << kill.signal_after_s << " s";
    for (const auto& [name, bytes] : want) {
      ASSERT_TRUE(got.count(name)) << name << " missing after resume";
      EXPECT_TRUE(got.at(name) == bytes)
          << name << " differs after a kill at " << kill.signal_after_s << " s and resume";
    }
    EXPECT_NE(slurp(dir / "run.json").find("\"sessions\": 2"), std::string::npos);
  }
}

// a small tapping pile (90 decagons, early rest on: the clock's rest state is checkpointed
// too) and a 2000-disk randomly forced fluid (over 1000 contacts per step: the force loop
// runs on both threads); checkpoints every few thousand steps
const std::vector<std::string> kTapping = {kSource + "/scenes/tap_small_negative_g.toml",
                                           "--set",
                                           "species[0].count=40",
                                           "--set",
                                           "species[1].count=50",
                                           "--set",
                                           "drive.taps=3",
                                           "--set",
                                           "preparation.settle_time=0.6",
                                           "--set",
                                           "output.checkpoint_steps=3000"};
// the same pile with the quench on: its state (armed, last kinetic energy, rising) is in the
// clock's checkpoint entry, and a resumed run must reset at the same steps
std::vector<std::string> with_quench(std::vector<std::string> a) {
  a.insert(a.end(), {"--set", "drive.quench=true"});
  return a;
}
const std::vector<std::string> kRfm = {kSource + "/scenes/rfm2d_reference.toml",
                                       "--set",
                                       "scene.duration=0.03",
                                       "--set",
                                       "rfm.discard_time=0.01",
                                       "--set",
                                       "rfm.sample_every=500",
                                       "--set",
                                       "output.checkpoint_steps=4000"};

INSTANTIATE_TEST_SUITE_P(Scenes, KillResume,
                         ::testing::Values(Case{"tap1", kTapping, "1"}, Case{"tap2", kTapping, "2"},
                                           Case{"tapquench1", with_quench(kTapping), "1"},
                                           Case{"rfm1", kRfm, "1"}, Case{"rfm2", kRfm, "2"}),
                         [](const auto& info) { return info.param.label; });

// SIGINT: the step finishes, a checkpoint is written, exit code 4 with the resume command.
// The signal goes when the run's first periodic checkpoint appears (an observed event, not a
// moment: a loaded machine can make any fixed moment too early or too late)
TEST(Resume, SigintCheckpointsAndSaysHowToResume) {
  const fs::path tmp = fresh("sigint");
  const auto args = with_out(kTapping, tmp / "ref");
  double wall = 0.0;
  ASSERT_EQ(timed_run(args, tmp / "ref.log", wall).code, 0);
  Launch stop;
  stop.signal = SIGINT;
  stop.signal_when = testing::new_checkpoint_in(tmp / "run");
  const Outcome o = run_binary(with_out(kTapping, tmp / "run"), tmp / "run.log", stop);
  ASSERT_TRUE(o.exited);
  ASSERT_EQ(o.code, 4) << o.output;
  EXPECT_NE(o.output.find("gransim resume " + (tmp / "run").string()), std::string::npos)
      << o.output;
  EXPECT_NE(slurp(tmp / "run" / "run.json").find("\"status\": \"interrupted\""), std::string::npos);
  // a checkpoint is a snapshot `gransim render` can draw
  std::string ck;
  for (const auto& e : fs::directory_iterator(tmp / "run"))
    if (e.path().extension() == ".gsck") ck = e.path().string();
  const Outcome pic = run_binary(
      {"render", ck, "-o", (tmp / "ck.png").string(), "--renderer", "software"}, tmp / "pic.log");
  EXPECT_EQ(pic.code, 0) << pic.output;
  EXPECT_NE(pic.output.find("from the checkpoint"), std::string::npos) << pic.output;
  EXPECT_GT(fs::file_size(tmp / "ck.png"), 10000u);
  const double cpu1 = nlohmann::json::parse(slurp(tmp / "run" / "run.json"))["cpu_time_s"];
  const Outcome r = run_binary({"resume", (tmp / "run").string(), "--quiet"}, tmp / "r.log");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(outputs(tmp / "run"), outputs(tmp / "ref"));
  // the run's CPU time is carried over by the checkpoint: both sessions are in it
  const auto rj = nlohmann::json::parse(slurp(tmp / "run" / "run.json"));
  EXPECT_EQ(rj["sessions"], 2);
  EXPECT_EQ(rj["cpu_time_sessions"], 2);
  EXPECT_GT(cpu1, 0.0);
  EXPECT_GT(rj["cpu_time_s"].get<double>(), 0.0);
  // a completed run has nothing to resume
  const Outcome again = run_binary({"resume", (tmp / "run").string()}, tmp / "again.log");
  EXPECT_EQ(again.code, 0);
  EXPECT_NE(again.output.find("nothing to resume"), std::string::npos) << again.output;
}

// the newest checkpoint damaged (a crash while copying, a bad disk): resume says so, takes
// the one before, and still ends bitwise equal
TEST(Resume, DamagedNewestCheckpointFallsBackToThePreviousOne) {
  const fs::path tmp = fresh("damaged");
  double wall = 0.0;
  ASSERT_EQ(timed_run(with_out(kTapping, tmp / "ref"), tmp / "ref.log", wall).code, 0);
  Launch stop;
  stop.signal = SIGINT;
  // checkpoints every 3000 of its ≈ 10⁵ steps: the first, then the one written on the way out
  stop.signal_when = testing::new_checkpoint_in(tmp / "run");
  ASSERT_EQ(run_binary(with_out(kTapping, tmp / "run"), tmp / "run.log", stop).code, 4);
  std::vector<fs::path> cks;
  for (const auto& e : fs::directory_iterator(tmp / "run"))
    if (e.path().filename().string().rfind("checkpoint-", 0) == 0) cks.push_back(e.path());
  ASSERT_EQ(cks.size(), 2u) << "the newest two checkpoints are kept";
  std::sort(cks.begin(), cks.end());
  {
    std::fstream f(cks.back(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x5a');
  }
  const Outcome r = run_binary({"resume", (tmp / "run").string(), "--quiet"}, tmp / "r.log");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("skipping " + cks.back().string()), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("checksum"), std::string::npos) << r.output;
  EXPECT_EQ(outputs(tmp / "run"), outputs(tmp / "ref"));
}

// a full disk (every file limited to 25 kB): the run stops with exit code 5 and a message
// naming the file and the reason, every row on disk is complete, and once there is room
// `gransim resume` ends with exactly the uninterrupted run's files
TEST(Resume, FullDiskKeepsEveryCompleteRowAndResumes) {
  const fs::path tmp = fresh("full");
  ASSERT_EQ(run_binary(with_out(kTapping, tmp / "ref"), tmp / "ref.log").code, 0);
  Launch full;
  full.file_size_limit = 25000;  // checkpoints ≈ 20 kB fit, series.csv (38 kB) does not
  const Outcome o = run_binary(with_out(kTapping, tmp / "run"), tmp / "run.log", full);
  ASSERT_TRUE(o.exited) << "killed by signal " << o.code;
  ASSERT_EQ(o.code, 5) << o.output;
  EXPECT_NE(o.output.find("series.csv: write failed: File too large"), std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("gransim resume"), std::string::npos) << o.output;
  for (const char* f : {"series.csv", "taps.csv", "segregation.csv"}) {
    const std::string text = slurp(tmp / "run" / f);
    ASSERT_FALSE(text.empty()) << f;
    EXPECT_EQ(text.back(), '\n') << f << " ends in a partial row";
    // every row has the header's number of fields
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    const auto fields = std::count(line.begin(), line.end(), ',');
    while (std::getline(in, line))
      ASSERT_EQ(std::count(line.begin(), line.end(), ','), fields) << f;
  }
  EXPECT_LT(fs::file_size(tmp / "run" / "series.csv"), fs::file_size(tmp / "ref" / "series.csv"));
  const Outcome r = run_binary({"resume", (tmp / "run").string(), "--quiet"}, tmp / "r.log");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(outputs(tmp / "run"), outputs(tmp / "ref"));
}

// a sweep stopped with SIGTERM passes it on to its runs, which checkpoint; the same sweep
// command again resumes them (no --force) and ends with the uninterrupted sweep's files
TEST(Resume, InterruptedSweepResumesItsRuns) {
  const fs::path tmp = fresh("sweep");
  auto sweep = [&](const fs::path& out) {
    std::vector<std::string> a = kTapping;
    a.insert(a.begin(), "sweep");
    a.insert(a.end(),
             {"--param", "drive.g_p=4,8", "--jobs", "2", "--quiet", "--out", out.string()});
    return a;
  };
  Launch env;
  env.env = {"GS_SWEEP_NO_MPI=1"};
  env.alarm_s = 120;
  double wall = 0.0;
  ASSERT_EQ(timed_run(sweep(tmp / "ref"), tmp / "ref.log", wall, env).code, 0);
  Launch stop = env;
  stop.signal = SIGTERM;
  // when the first run has checkpointed (both run at once)
  stop.signal_when = testing::new_checkpoint_in(tmp / "run" / "g_p=4");
  const Outcome o = run_binary(sweep(tmp / "run"), tmp / "run.log", stop);
  ASSERT_TRUE(o.exited);
  ASSERT_EQ(o.code, 4) << o.output;
  EXPECT_GT(list_size(tmp / "run" / "g_p=4"), 0u);
  // the stopped runs are said to be interrupted, not failed, in the message and the manifest
  EXPECT_NE(o.output.find("g_p=4: interrupted (exit 4"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("failed"), std::string::npos) << o.output;
  EXPECT_NE(slurp(tmp / "run" / "sweep.json").find("\"interrupted\""), std::string::npos);
  const Outcome r = run_binary(sweep(tmp / "run"), tmp / "r.log", env);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* run : {"g_p=4", "g_p=8"})
    EXPECT_EQ(outputs(tmp / "run" / run), outputs(tmp / "ref" / run)) << run;
  EXPECT_NE(slurp(tmp / "run" / "g_p=4" / "run.json").find("\"sessions\": 2"), std::string::npos);
}

TEST(Resume, NothingToResumeIsBadInput) {
  const fs::path tmp = fresh("none");
  const Outcome missing = run_binary({"resume", (tmp / "nope").string()}, tmp / "a.log");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.output.find("does not exist"), std::string::npos) << missing.output;
  const Outcome empty = run_binary({"resume", tmp.string()}, tmp / "b.log");
  EXPECT_EQ(empty.code, 2);
  EXPECT_NE(empty.output.find("no checkpoint"), std::string::npos) << empty.output;
}

}  // namespace
}  // namespace gs

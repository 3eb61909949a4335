// a command never writes over a file it reads, deletes only files it wrote, and checks what it
// can before it touches the disk: `analyze --out` over its own input series, a resume among
// files that only look like its snapshots, `run --force` whose new scene fails its first
// health check
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::Launch;
using testing::run_binary;
using testing::slurp;

// ten disks in a periodic box, 1 µs steps (the hostile corpus's base scene)
const char* kDisks = R"([scene]
name = "own_files"
duration = 0.004

[model]
kind = "S"

[[material]]
name = "glass"
ks = 5e5
eps_n = 0.6
eps_t = 1.0

[[species]]
name = "bead"
shape = "disk"
radius = 0.0015
mass = 3.53e-5
count = 10

[box]
kind = "periodic"
width = 0.05

[integrator]
kind = "velocity_verlet"
dt = 1e-6

[drive]
kind = "none"
)";

// every regular file under `dir` with its bytes
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != ".lock")
      out[fs::relative(e.path(), dir).string()] = slurp(e.path());
  return out;
}

TEST(OwnFiles, AnalyzeRefusesAnOutThatHoldsItsInputSeries) {
  const fs::path tmp = testing::fresh_test_dir("gs_own_files");
  const fs::path in = tmp / "data";
  fs::create_directories(in / "deeper");
  // the inputs are named as the analysis names its own tables
  for (const fs::path& f : {in / "series.csv", in / "deeper" / "summary.csv"}) {
    std::ofstream s(f);
    s << "tap,phi\n";
    for (int k = 1; k <= 60; ++k) s << k << "," << 0.80 + 0.001 * (k * 7 % 11) << "\n";
  }
  const auto before = contents(in);
  const std::string a = "negative_g:4:" + (in / "series.csv").string(),
                    b = "negative_g:6:" + (in / "deeper" / "summary.csv").string();
  for (const fs::path& out : {in, in / "deeper", fs::path(in.string() + "/")}) {
    const auto o = run_binary({"analyze", "--series", a, "--series", b, "--test-area", "0.01",
                               "--out", out.string(), "--no-charts", "-q"},
                              tmp / "log.txt");
    EXPECT_EQ(o.code, 2) << out << "\n" << o.output;
    EXPECT_NE(o.output.find("--out"), std::string::npos) << o.output;
    EXPECT_NE(o.output.find("input"), std::string::npos) << o.output;
    EXPECT_EQ(contents(in), before) << "an input was written over by --out " << out;
  }
  // a folder beside the inputs is fine
  const auto ok = run_binary({"analyze", "--series", a, "--series", b, "--test-area", "0.01",
                              "--out", (tmp / "analysis").string(), "--no-charts", "-q"},
                             tmp / "log.txt");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_EQ(contents(in), before);
  fs::remove_all(tmp);
}

TEST(OwnFiles, AResumeRemovesOnlyTheSnapshotsItWrote) {
  const fs::path tmp = testing::fresh_test_dir("gs_own_files");
  std::ofstream(tmp / "disks.toml") << kDisks
                                    << "\n[output]\ncheckpoint_steps = 1000\n"
                                       "\n[output.snapshots]\nevery_time = 0.0005\n"
                                       "formats = [\"vtp\"]\n";
  const fs::path dir = tmp / "run";
  Launch stop;
  stop.alarm_s = 120;
  stop.signal = SIGINT;
  stop.signal_when = testing::new_checkpoint_in(dir);
  const auto first = run_binary({"run", (tmp / "disks.toml").string(), "--out", dir.string(), "-q"},
                                tmp / "first.log", stop);
  ASSERT_EQ(first.code, 4) << first.output;
  // files that look like later snapshots but are not this run's: another extension, a number
  // written otherwise or too large for any counter, a format the scene does not write, a folder
  const fs::path snaps = dir / "snapshots";
  const char* foreign[] = {
      "snap_000999.txt", "snap_999.vtp",        "snap_99999999999999999999999.vtp",
      "snap_000999.xyz", "contacts_000999.txt", "snap_000999.vtp.bak"};
  for (const char* f : foreign) std::ofstream(snaps / f) << "mine\n";
  fs::create_directories(snaps / "snap_000998.vtp");
  std::ofstream(snaps / "snap_000998.vtp" / "inside.txt") << "mine\n";
  // and one the run itself would write later: it goes
  std::ofstream(snaps / "snap_000999.vtp") << "stale\n";
  Launch quick;
  quick.alarm_s = 120;
  const auto r = run_binary({"resume", dir.string(), "-q"}, tmp / "resume.log", quick);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
  for (const char* f : foreign) EXPECT_EQ(slurp(snaps / f), "mine\n") << f;
  EXPECT_EQ(slurp(snaps / "snap_000998.vtp" / "inside.txt"), "mine\n");
  EXPECT_FALSE(fs::exists(snaps / "snap_000999.vtp"));
  EXPECT_TRUE(fs::exists(snaps / "snap_000008.vtp"));  // t = 0.004 s: snapshots 0 … 8
  fs::remove_all(tmp);
}

TEST(OwnFiles, ForceKeepsTheOldRunWhenTheNewFailsItsFirstHealthCheck) {
  const fs::path tmp = testing::fresh_test_dir("gs_own_files");
  std::ofstream(tmp / "good.toml") << kDisks;
  const fs::path dir = tmp / "run";
  const auto old = run_binary({"run", (tmp / "good.toml").string(), "--out", dir.string(), "-q"},
                              tmp / "old.log");
  ASSERT_EQ(old.code, 0) << old.output;
  std::ofstream(dir / "notes.txt") << "my notes on this run\n";
  const auto before = contents(dir);
  // two grains placed almost on top of each other: the first health check (after one step)
  // finds the overlap
  std::ofstream(tmp / "bad.toml") << std::string(kDisks).replace(
                                         std::string(kDisks).find("count = 10"), 10, "count = 2")
                                  << "\n[health]\ncheck_every = 1\nmax_overlap = 0.05\n"
                                     "\n[[preparation.particle]]\nx = 0.01\ny = 0.01\n"
                                     "\n[[preparation.particle]]\nx = 0.0101\ny = 0.01\n";
  const auto bad =
      run_binary({"run", (tmp / "bad.toml").string(), "--out", dir.string(), "--force", "-q"},
                 tmp / "bad.log");
  ASSERT_EQ(bad.code, 3) << bad.output;
  EXPECT_NE(bad.output.find("as it was"), std::string::npos) << bad.output;
  EXPECT_EQ(contents(dir), before);
  EXPECT_FALSE(fs::exists(dir / ".gransim-replaced"));
  // a sound new scene replaces the old run
  const auto good =
      run_binary({"run", (tmp / "good.toml").string(), "--out", dir.string(), "--force", "-q"},
                 tmp / "good.log");
  ASSERT_EQ(good.code, 0) << good.output;
  EXPECT_FALSE(fs::exists(dir / "notes.txt"));
  EXPECT_FALSE(fs::exists(dir / ".gransim-replaced"));
  EXPECT_TRUE(fs::exists(dir / "run.json"));
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs

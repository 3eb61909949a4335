// sweeps over MPI ranks and replicas, end to end through the gransim binary: a 2-rank sweep
// (`mpirun -np 2 gransim sweep …`) writes byte for byte the files of a serial sweep (wall
// times aside), resumes a partly finished sweep without touching completed runs, and stops
// with exit 2 on every rank on bad input; replicas get their own seeds and `analyze` sees them
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::slurp;

using Result = testing::ShellResult;
using testing::gransim;
using testing::sh;

// two ranks on this machine, as root too (containers, CI)
std::string mpirun2(const std::string& args) {
  return std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 GS_PYTHON_DIR=") +
         GS_SOURCE_DIR + "/python mpirun --oversubscribe -np 2 " + GS_BINARY + " " + args;
}

// run.json and sweep.json without what depends on the machine's speed (wall times, rates)
std::string without_wall_times(const std::string& text) {
  // (the step's profile too: its stages' wall times and the step loop's)
  static const std::regex wall(
      R"re("(wall_time\w*|cpu_time_s|particle_steps_per_s|omp_\w+|step_loop_s|profile_timed_steps|drive|predict|broad_phase|pairs|accelerate|kick|correct|predict_next|place_next|health)": [-+.0-9e]+)re");
  return std::regex_replace(text, wall, "\"$1\": -");
}

// why an MPI test cannot run here ("" when it can)
std::string mpi_unavailable() {
#ifndef GS_HAVE_MPI
  return "gransim was built without MPI";
#else
  if (sh("command -v mpirun").code != 0) return "mpirun is not installed";
  return "";
#endif
}

// 40 decagons in a 0.1 m box, velocity Verlet: 0.5 s of settling, then `taps` taps of
// T = 0.5 s (about 0.2 s of wall time per tap)
class SweepMpi : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::fresh_test_dir("gs_test_sweep_mpi");
    scene_ = (dir_ / "tiny.toml").string();
    std::ofstream(scene_) << testing::tiny_tapping_scene(4);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string scene_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

TEST_F(SweepMpi, TwoRanksWriteTheFilesOfASerialSweep) {
  if (const std::string why = mpi_unavailable(); !why.empty()) GTEST_SKIP() << why;
  const std::string args = "sweep " + scene_ + " --param drive.g_p=2,4 --replicas 2 -q --out ";
  auto t0 = std::chrono::steady_clock::now();
  Result r = sh(gransim(args + (dir_ / "serial").string() + " --jobs 1"));
  const double serial = seconds_since(t0);
  ASSERT_EQ(r.code, 0) << r.output;
  t0 = std::chrono::steady_clock::now();
  r = sh(mpirun2(args + (dir_ / "mpi").string()));
  const double mpi = seconds_since(t0);
  ASSERT_EQ(r.code, 0) << r.output;
  std::printf("[ timing   ] 4 runs: serial --jobs 1 %.2f s, mpirun -np 2 %.2f s\n", serial, mpi);

  // every file of the serial sweep, and no other, with the same bytes; logs and checkpoints
  // (these hold wall-clock data, "run/clock") aside
  std::set<std::string> serial_files, mpi_files;
  for (const auto& [root, files] :
       {std::pair{dir_ / "serial", &serial_files}, std::pair{dir_ / "mpi", &mpi_files}})
    for (const auto& e : fs::recursive_directory_iterator(root))
      if (e.is_regular_file() && e.path().filename() != ".lock")  // a lock holds its PID
        files->insert(fs::relative(e.path(), root).string());
  EXPECT_EQ(serial_files, mpi_files);
  int compared = 0;
  for (const std::string& f : serial_files) {
    if (f.rfind("logs/", 0) == 0 || f.ends_with(".gsck")) continue;
    SCOPED_TRACE(f);
    std::string a = slurp(dir_ / "serial" / f), b = slurp(dir_ / "mpi" / f);
    if (f.ends_with(".json")) {
      a = without_wall_times(a);
      b = without_wall_times(b);
    }
    EXPECT_TRUE(a == b) << "differs between the serial and the 2-rank sweep";
    ++compared;
  }
  for (const char* run : {"g_p=2", "g_p=4", "g_p=2_rep=1", "g_p=4_rep=1"})
    for (const char* f : {"taps.csv", "series.csv", "state.csv", "scene.toml", "run.json"})
      EXPECT_TRUE(serial_files.count(std::string(run) + "/" + f)) << run << "/" << f;
  EXPECT_GE(compared, 4 * 6 + 1);

  // a replica is another realisation: its own seed, another pile
  const std::string manifest = slurp(dir_ / "mpi" / "sweep.json");
  EXPECT_NE(manifest.find("\"replicas\": 2"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("\"preparation.seed="), std::string::npos) << manifest;
  EXPECT_NE(slurp(dir_ / "mpi" / "g_p=2" / "taps.csv"),
            slurp(dir_ / "mpi" / "g_p=2_rep=1" / "taps.csv"));
  EXPECT_NE(slurp(dir_ / "mpi" / "g_p=2" / "scene.toml").find("seed = 5\n"), std::string::npos);
  EXPECT_EQ(slurp(dir_ / "mpi" / "g_p=2_rep=1" / "scene.toml").find("seed = 5\n"),
            std::string::npos);
}

TEST_F(SweepMpi, ResumesAPartlyFinishedSweep) {
  if (const std::string why = mpi_unavailable(); !why.empty()) GTEST_SKIP() << why;
  const fs::path sw = dir_ / "sweep";
  // the first value done by a serial sweep
  Result r = sh(gransim("sweep " + scene_ + " --param drive.g_p=2 -q --out " + sw.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  const auto stamp = fs::last_write_time(sw / "g_p=2" / "taps.csv");
  const std::string taps = slurp(sw / "g_p=2" / "taps.csv");
  const std::string run_json = slurp(sw / "g_p=2" / "run.json");

  // an unfinished run directory stops the MPI sweep on every rank before anything runs
  fs::create_directories(sw / "g_p=6");
  std::ofstream(sw / "g_p=6" / "run.json") << "{\n  \"status\": \"interrupted\"\n}\n";
  r = sh(mpirun2("sweep " + scene_ + " --param drive.g_p=2,4,6 -q --out " + sw.string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("unfinished"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(sw / "g_p=4"));
  // the message once (rank 0), not once per rank
  EXPECT_EQ(r.output.find("unfinished"), r.output.rfind("unfinished")) << r.output;

  // with --force: the two missing values run on the ranks, the completed one is kept as it is
  r = sh(mpirun2("sweep " + scene_ + " --param drive.g_p=2,4,6 --force --out " + sw.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("1 already completed"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(sw / "g_p=2" / "taps.csv"), stamp);
  EXPECT_EQ(slurp(sw / "g_p=2" / "taps.csv"), taps);
  EXPECT_EQ(slurp(sw / "g_p=2" / "run.json"), run_json);
  for (const char* run : {"g_p=4", "g_p=6"})
    EXPECT_NE(slurp(sw / run / "run.json").find("\"status\": \"completed\""), std::string::npos)
        << run;
  const std::string manifest = slurp(sw / "sweep.json");
  EXPECT_NE(manifest.find("\"name\": \"g_p=2\", \"dir\": \"g_p=2\", \"overrides\": "
                          "[\"drive.g_p=2\"], \"state\": \"skipped\""),
            std::string::npos)
      << manifest;
  EXPECT_NE(manifest.find("\"status\": \"finished\""), std::string::npos) << manifest;

  // again: nothing left to do
  r = sh(mpirun2("sweep " + scene_ + " --param drive.g_p=2,4,6 -q --out " + sw.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("3 already completed"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(sw / "g_p=2" / "taps.csv"), stamp);
}

TEST_F(SweepMpi, BadInputStopsEveryRank) {
  if (const std::string why = mpi_unavailable(); !why.empty()) GTEST_SKIP() << why;
  const fs::path sw = dir_ / "sweep";
  Result r =
      sh(mpirun2("sweep " + scene_ + " --param drive.no_such_key=1,2 -q --out " + sw.string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("no_such_key"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("gransim: error"), r.output.rfind("gransim: error")) << r.output;
  EXPECT_FALSE(fs::exists(sw / "sweep.json"));
}

// replicas without MPI: the analysis sees one run per replica (they are not pooled)
TEST_F(SweepMpi, ReplicasAreAnalysedAsRuns) {
  std::ofstream(scene_) << testing::tiny_tapping_scene(22);
  const fs::path sw = dir_ / "sweep";
  Result r = sh(gransim("sweep " + scene_ + " --param drive.g_p=2 --replicas 2 --jobs 2 -q --out " +
                        sw.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  r = sh(gransim("analyze " + sw.string() + " --no-charts"));
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string summary = slurp(sw / "analysis" / "summary.csv");
  int rows = 0;
  for (char c : summary) rows += c == '\n';
  EXPECT_EQ(rows, 3) << summary;  // header and one row per replica
  EXPECT_NE(summary.find("g_p=2_rep=1"), std::string::npos) << summary;
}

}  // namespace
}  // namespace gs

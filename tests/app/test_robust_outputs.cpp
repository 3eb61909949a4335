// outputs under pressure and runs that must not pass for completed: a model's CSV on a full
// disk keeps whole rows (exit 5), a resume refuses an edited scene.toml, a blown-up state is
// never "completed" whatever the health-check interval
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::Launch;
using testing::run_binary;
using testing::slurp;

const std::string kBase = std::string(GS_SOURCE_DIR) + "/tests/app/hostile/good_base.toml";

// every line of a CSV (after # lines) has the header's number of fields, and the file ends in
// a line end
void expect_whole_rows(const fs::path& f) {
  const std::string text = slurp(f);
  ASSERT_FALSE(text.empty()) << f;
  EXPECT_EQ(text.back(), '\n') << f << " ends in a partial row";
  std::istringstream in(text);
  std::string line;
  long fields = -1;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const long n = std::count(line.begin(), line.end(), ',');
    if (fields < 0) fields = n;
    EXPECT_EQ(n, fields) << f << ": " << line;
  }
}

// a full disk (every file limited to 3000 bytes) under `gransim model`: exit 5 naming the file,
// no internal error, every row on disk complete
TEST(RobustOutputs, ModelOnAFullDiskKeepsWholeRowsAndExitsFive) {
  const fs::path tmp = testing::fresh_test_dir("gs-robust");
  Launch full;
  full.file_size_limit = 3000;
  const auto o = run_binary({"model", "bisection", "--levels", "8", "--realisations", "200",
                             "--bins", "400", "--out", (tmp / "m").string(), "--no-charts", "-q"},
                            tmp / "log.txt", full);
  ASSERT_TRUE(o.exited) << "killed by signal " << o.code;
  EXPECT_EQ(o.code, 5) << o.output;
  EXPECT_NE(o.output.find("bisection.csv: write failed"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("every complete row is kept"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
  expect_whole_rows(tmp / "m" / "bisection.csv");
  EXPECT_LE(fs::file_size(tmp / "m" / "bisection.csv"), 3000u);
  fs::remove_all(tmp);
}

// a full disk under `analyze` and `movie`: exit 5 naming the file, and no partial file left
// (each table is whole or absent; a movie that could not be finished is removed)
TEST(RobustOutputs, AnalyzeAndMovieOnAFullDiskLeaveNoPartialFile) {
  const fs::path tmp = testing::fresh_test_dir("gs-robust");
  {
    std::ofstream s(tmp / "g6.csv");
    s << "tap,phi\n";
    for (int k = 1; k <= 200; ++k) s << k << "," << 0.80 + 0.001 * (k * 7 % 11) << "\n";
  }
  Launch full;
  full.file_size_limit = 2000;
  const auto a =
      run_binary({"analyze", "--series", "negative_g:6:" + (tmp / "g6.csv").string(), "--test-area",
                  "0.01", "--out", (tmp / "a").string(), "--no-charts", "-q"},
                 tmp / "analyze.log", full);
  ASSERT_TRUE(a.exited) << "killed by signal " << a.code;
  EXPECT_EQ(a.code, 5) << a.output;
  EXPECT_NE(a.output.find((tmp / "a").string()), std::string::npos) << a.output;
  EXPECT_NE(a.output.find("File too large"), std::string::npos) << a.output;
  for (const auto& e : fs::directory_iterator(tmp / "a")) {
    if (e.path().filename() == ".lock") continue;
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
    EXPECT_GT(fs::file_size(e.path()), 0u) << e.path() << " is empty";
  }
  // the same analysis with room: every table
  const auto ok =
      run_binary({"analyze", "--series", "negative_g:6:" + (tmp / "g6.csv").string(), "--test-area",
                  "0.01", "--out", (tmp / "b").string(), "--no-charts", "-q"},
                 tmp / "analyze.log");
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_TRUE(fs::exists(tmp / "b" / "series.csv"));

  // a movie of the fixture run's frames into 1500 bytes
  const fs::path run = tmp / "run";
  fs::copy(fs::path(GS_SOURCE_DIR) / "tests/app/hostile/fixture_run", run,
           fs::copy_options::recursive);
  full.file_size_limit = 1500;
  const auto m = run_binary({"movie", run.string(), "-o", (tmp / "m.mp4").string(), "-q"},
                            tmp / "movie.log", full);
  ASSERT_TRUE(m.exited) << "killed by signal " << m.code;
  if (m.output.find("without FFmpeg") == std::string::npos) {
    EXPECT_EQ(m.code, 5) << m.output;
    EXPECT_NE(m.output.find("m.mp4"), std::string::npos) << m.output;
    EXPECT_FALSE(fs::exists(tmp / "m.mp4")) << "a partial movie is left";
  }
  fs::remove_all(tmp);
}

// a resume continues the run with the scene it started with: an edited scene.toml is refused
// (exit 2, naming the file and the changed line); restored, the resume goes on
TEST(RobustOutputs, ResumeRefusesAnEditedSceneToml) {
  const fs::path tmp = testing::fresh_test_dir("gs-robust");
  const fs::path dir = tmp / "run";
  Launch stop;
  stop.alarm_s = 120;
  stop.signal = SIGINT;
  stop.signal_when = testing::new_checkpoint_in(dir);
  const auto first = run_binary({"run", kBase, "--out", dir.string(), "-q", "--set",
                                 "scene.duration=20", "--set", "output.checkpoint_steps=2000"},
                                tmp / "first.log", stop);
  ASSERT_EQ(first.code, 4) << first.output;
  const std::string scene = slurp(dir / "scene.toml");
  std::string edited = scene;
  const auto at = edited.find("eps_n = ");
  ASSERT_NE(at, std::string::npos) << scene;
  edited.replace(at, 8, "eps_n = 0.3 #");
  std::ofstream(dir / "scene.toml") << edited;
  const auto refused = run_binary({"resume", dir.string(), "-q"}, tmp / "refused.log");
  EXPECT_EQ(refused.code, 2) << refused.output;
  EXPECT_NE(refused.output.find((dir / "scene.toml").string()), std::string::npos)
      << refused.output;
  EXPECT_NE(refused.output.find("edited"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("eps_n"), std::string::npos) << refused.output;
  // restored: the resume proceeds (stopped again at its first checkpoint)
  std::ofstream(dir / "scene.toml") << scene;
  stop.signal_when = testing::new_checkpoint_in(dir);
  const auto again = run_binary({"resume", dir.string(), "-q"}, tmp / "again.log", stop);
  EXPECT_EQ(again.code, 4) << again.output;
  fs::remove_all(tmp);
}

// an unstable run (allowed on purpose) with health checks far apart: it blows up between two
// checks; the run stops with exit 3 (or the health check's message), never a crash, never
// "completed"
TEST(RobustOutputs, BlownUpStateIsNeverCompleted) {
  const fs::path tmp = testing::fresh_test_dir("gs-robust");
  for (const char* every : {"100", "1000000000"}) {
    const auto o =
        run_binary({"run", kBase, "--out", (tmp / "run").string(), "--force", "-q",
                    "--allow-unstable", "--set", "integrator.dt=2e-4", "--set",
                    "scene.duration=0.5", "--set", std::string("health.check_every=") + every,
                    "--set", "health.max_overlap=1.0", "--set", "preparation.velocity_amplitude=5"},
                   tmp / "log.txt");
    ASSERT_TRUE(o.exited) << every << ": killed by signal " << o.code << "\n" << o.output;
    EXPECT_EQ(o.code, 3) << every << "\n" << o.output;
    EXPECT_EQ(o.output.find("completed"), std::string::npos) << o.output;
    EXPECT_EQ(slurp(tmp / "run" / "run.json").find("\"status\": \"completed\""), std::string::npos);
  }
  fs::remove_all(tmp);
}

}  // namespace
}  // namespace gs

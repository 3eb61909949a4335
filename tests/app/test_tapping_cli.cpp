// the tapping study end to end through the gransim binary: a sweep of a tiny pile writes one
// run directory per value with taps.csv and segregation.csv, `analyze` writes the statistics and
// the charts, a repeated sweep skips finished runs and redoes unfinished ones only with --force,
// and bad --param arguments stop with exit code 2 and a message naming the argument
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::slurp;

using Result = testing::ShellResult;
using testing::gransim;
using testing::sh;

// a CSV file as header + rows of numbers
struct Table {
  std::vector<std::string> head;
  std::vector<std::vector<double>> rows;
  int col(const std::string& name) const {
    for (std::size_t k = 0; k < head.size(); ++k)
      if (head[k] == name) return static_cast<int>(k);
    return -1;
  }
};

Table read_csv(const fs::path& p) {
  Table t;
  std::ifstream in(p);
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<std::string> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (first) {
      t.head = cells;
      first = false;
      continue;
    }
    std::vector<double> v;
    for (const auto& c : cells) v.push_back(std::strtod(c.c_str(), nullptr));
    t.rows.push_back(v);
  }
  return t;
}

// 40 decagons (18 big, 22 small) in a 0.1 m box; velocity Verlet at Δt = 1e-4 s (contact time
// 6.9e-4 s), 0.5 s of settling, 22 taps of T = 0.5 s with 0.01 s pulses: a few seconds per run
const std::string kTinyScene = testing::tiny_tapping_scene(22);

class TappingCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::fresh_test_dir("gs_test_tapping");
    scene_ = (dir_ / "tiny.toml").string();
    std::ofstream(scene_) << kTinyScene;
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string scene_;
};

bool python_charts_available() {
  return sh("/usr/bin/python3 -c 'import numpy, matplotlib'").code == 0;
}

// checks on one finished run directory of the tiny sweep
void expect_tap_run(const fs::path& run, double g_p) {
  SCOPED_TRACE(run.string());
  const Table taps = read_csv(run / "taps.csv");
  for (const char* c :
       {"tap", "t", "phi", "phi_left", "phi_right", "kinetic_energy", "max_speed", "z_mean",
        "z_big", "z_small", "coordination", "S_xx", "S_xy", "S_yx", "S_yy", "relax_end", "early"})
    EXPECT_GE(taps.col(c), 0) << "column " << c;
  // the prepared pile (tap 0) and 22 taps, each measured just before the next pulse:
  // t = settle + k·T to the step
  ASSERT_EQ(taps.rows.size(), 23u);
  for (std::size_t k = 0; k < taps.rows.size(); ++k) {
    const auto& r = taps.rows[k];
    EXPECT_EQ(r[taps.col("tap")], static_cast<double>(k));
    EXPECT_NEAR(r[taps.col("t")], 0.5 + 0.5 * static_cast<double>(k), 1e-9);
    // a plausible packing, at rest (40 grains of ≈ 2e-4 kg; 1e-5 J is ≈ 1 mm/s each)
    EXPECT_GT(r[taps.col("phi")], 0.65);
    EXPECT_LT(r[taps.col("phi")], 0.92);
    EXPECT_LT(r[taps.col("kinetic_energy")], 1e-5);
    EXPECT_GT(r[taps.col("coordination")], 2.0);
    EXPECT_LT(r[taps.col("S_yy")], 0.0);  // the pile's weight compresses it
    EXPECT_EQ(r[taps.col("early")], 0.0);
  }
  // n(h) on the fixed grid reaches every grain of each species at the top
  const Table seg = read_csv(run / "segregation.csv");
  ASSERT_EQ(seg.rows.size(), 23u);
  EXPECT_EQ(seg.rows.back()[seg.col("big@500")], 18.0);
  EXPECT_EQ(seg.rows.back()[seg.col("small@500")], 22.0);
  const std::string js = slurp(run / "run.json");
  EXPECT_NE(js.find("\"status\": \"completed\""), std::string::npos);
  EXPECT_NE(js.find("\"protocol\": \"negative_g\""), std::string::npos);
  EXPECT_NE(js.find("\"control\": " + std::to_string(static_cast<int>(g_p))), std::string::npos);
  EXPECT_NE(js.find("\"taps_done\": 22"), std::string::npos);
}

TEST_F(TappingCli, SweepAnalyzeAndContinue) {
  const fs::path sw = dir_ / "sweep";
  // a sweep of two values, both at once
  Result r = sh(gransim("sweep " + scene_ + " --param drive.g_p=2,4 --out " + sw.string() +
                        " --jobs 2 --quiet"));
  ASSERT_EQ(r.code, 0) << r.output;
  expect_tap_run(sw / "g_p=2", 2.0);
  expect_tap_run(sw / "g_p=4", 4.0);
  EXPECT_NE(slurp(sw / "sweep.json").find("\"key\": \"drive.g_p\""), std::string::npos);

  // the analysis of the sweep directory: statistics of both runs, the charts when python can
  r = sh(gransim("analyze " + sw.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path an = sw / "analysis";
  const Table summary = read_csv(an / "summary.csv");
  ASSERT_EQ(summary.rows.size(), 2u) << r.output;
  for (const auto& row : summary.rows) {
    EXPECT_EQ(row[summary.col("n_used")], 20.0);  // 22 taps, 2 discarded (tap 0 is not a tap)
    EXPECT_GT(row[summary.col("phi_mean")], 0.65);
    EXPECT_GT(row[summary.col("sigma")], 0.0);  // the packing changes from tap to tap
  }
  for (const char* f : {"series.csv", "kde.csv", "analysis.json", "runs.csv"})
    EXPECT_TRUE(fs::exists(an / f)) << f;
  if (python_charts_available()) {
    for (const char* png :
         {"fig4_series.png", "fig5_mean_sigma_negative_g.png", "fig7a_kde_negative_g.png",
          "taprun_rest.png", "taprun_segregation.png", "fig12_stress_phi.png"}) {
      ASSERT_TRUE(fs::exists(an / png)) << png << "\n" << r.output;
      EXPECT_GT(fs::file_size(an / png), 10000u) << png;  // a drawn chart, not an empty canvas
      EXPECT_EQ(slurp(an / png).substr(1, 3), "PNG") << png;
    }
  } else {
    std::printf("[ skipped  ] charts: /usr/bin/python3 with numpy and matplotlib not available\n");
  }

  // continuation: finished runs are skipped; an unfinished directory needs --force
  const auto stamp = fs::last_write_time(sw / "g_p=2" / "taps.csv");
  const std::string taps2 = slurp(sw / "g_p=2" / "taps.csv");
  fs::create_directories(sw / "g_p=6");
  std::ofstream(sw / "g_p=6" / "run.json") << "{\n  \"status\": \"interrupted\"\n}\n";
  r = sh(gransim("sweep " + scene_ + " --param drive.g_p=2,4,6 --out " + sw.string() +
                 " --jobs 1 --quiet"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("unfinished"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("g_p=6"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("--force"), std::string::npos) << r.output;
  r = sh(gransim("sweep " + scene_ + " --param drive.g_p=2,4,6 --out " + sw.string() +
                 " --jobs 1 --quiet --force"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("2 already completed"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(sw / "g_p=2" / "taps.csv"), stamp);
  EXPECT_EQ(slurp(sw / "g_p=2" / "taps.csv"), taps2);
  EXPECT_EQ(read_csv(sw / "g_p=6" / "taps.csv").rows.size(), 23u);
  const std::string manifest = slurp(sw / "sweep.json");
  EXPECT_NE(
      manifest.find("\"name\": \"g_p=2\", \"dir\": \"g_p=2\", \"overrides\": [\"drive.g_p=2\"], "
                    "\"state\": \"skipped\""),
      std::string::npos)
      << manifest;
  EXPECT_NE(manifest.find("\"state\": \"completed\""), std::string::npos) << manifest;

  // the same directory with another base scene is refused before anything runs
  r = sh(gransim("sweep " + scene_ + " --param drive.g_p=2 --set drive.taps=3 --out " +
                 sw.string() + " --quiet"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("different scene"), std::string::npos) << r.output;
}

TEST_F(TappingCli, BadParamExitsTwoWithAClearMessage) {
  const std::string out = " --out " + (dir_ / "bad").string() + " --quiet";
  struct Case {
    std::string param, expect;
  };
  for (const Case& c :
       {Case{"drive.g_p", "expected KEY=V1,V2"}, Case{"drive.g_pp=4,8", "drive.g_pp"},
        Case{"drive.g_p=-1,8", "must be > 0"}, Case{"drive.g_p=4,,8", "empty value"},
        Case{"drive.g_p=4,4", "appears twice"}, Case{"=4,8", "key before '=' is empty"}}) {
    const Result r = sh(gransim("sweep " + scene_ + " --param '" + c.param + "'" + out));
    EXPECT_EQ(r.code, 2) << c.param << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.param << "\n" << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << r.output;
  }
  // nothing was started
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
  // a sweep needs --param at all
  EXPECT_EQ(sh(gransim("sweep " + scene_ + out)).code, 2);
}

// a Δt beyond 1/5 of the contact time (here 0.29 t_c) is refused with exit 2, naming the key,
// and the limit it suggests (t_c/5 = 1.3778e-4 s for these grains on the wall, rounded down to
// 1.37e-4 s) is itself accepted
TEST_F(TappingCli, TooLargeStepIsRefusedWithASuggestionThatRuns) {
  const std::string out = " --quiet --set drive.taps=1 --set preparation.settle_time=0.01";
  Result r = sh(gransim("run " + scene_ + " --out " + (dir_ / "big").string() +
                        " --set integrator.dt=2e-4" + out));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("integrator.dt"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "big"));
  const std::size_t at = r.output.find("Use dt <= ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double suggested = std::strtod(r.output.c_str() + at + 10, nullptr);
  EXPECT_NEAR(suggested, 1.37e-4, 1e-12) << r.output;  // t_c/5 rounded down to 3 digits
  std::ostringstream dt;
  dt.precision(17);
  dt << suggested;
  r = sh(gransim("run " + scene_ + " --out " + (dir_ / "ok").string() +
                 " --set integrator.dt=" + dt.str() + out));
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST_F(TappingCli, AnalyzeRefusesDirectoriesWithoutTaps) {
  fs::create_directories(dir_ / "empty");
  Result r = sh(gransim("analyze " + (dir_ / "empty").string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("no tapping runs"), std::string::npos) << r.output;
  fs::create_directories(dir_ / "other");
  r = sh(gransim("analyze " + (dir_ / "empty").string() + " " + (dir_ / "other").string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gs

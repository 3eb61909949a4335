// `gransim study` end to end on the tiny matrix (scenes/studies/quick.toml): one CSV row per
// combination with the documented columns, the stability map, the charts when matplotlib is
// there; a deliberately unstable Δt is a recorded result with the health message; a bad study
// file stops with exit code 2 naming file, line and key
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "app/study/study.hpp"
#include "app/study/study_problems.hpp"
#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

using Result = testing::ShellResult;
using testing::gransim;
using testing::sh;

// a fresh scratch folder per test
fs::path scratch(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("gs_test_study_" + std::to_string(getpid()) + "_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// split one CSV line, honouring double-quoted fields with "" escapes
std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> f(1);
  bool quoted = false;
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    if (quoted && c == '"' && k + 1 < line.size() && line[k + 1] == '"') {
      f.back() += '"';
      ++k;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      f.emplace_back();
    } else {
      f.back() += c;
    }
  }
  return f;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(split_csv(line));
  return rows;
}

int column(const std::vector<std::string>& head, const std::string& name) {
  for (std::size_t k = 0; k < head.size(); ++k)
    if (head[k] == name) return static_cast<int>(k);
  return -1;
}

TEST(Study, QuickMatrixWritesOneRowPerCombinationAndCharts) {
  const fs::path out = scratch("quick") / "study";
  const Result r = sh(gransim(std::string("study ") + GS_SOURCE_DIR +
                              "/scenes/studies/quick.toml --quiet --out " + out.string()));
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows = read_csv(out / "study.csv");
  ASSERT_FALSE(rows.empty());
  const auto& head = rows[0];
  for (const char* c : {"problem", "integrator", "dt", "dt_over_tc", "broad_phase", "switches",
                        "wall_s", "particle_steps_per_s", "error", "error_kind", "stable", "note"})
    EXPECT_GE(column(head, c), 0) << "missing column " << c;
  // 2 integrators × 2 Δt for each problem; the pile (walled) also × 2 broad phases, the
  // tapping run × early rest on/off
  EXPECT_EQ(rows.size() - 1, 4u + 4u + 4u + 4u + 8u + 8u + 4u);
  const int stable = column(head, "stable"), err = column(head, "error");
  const int dto = column(head, "dt_over_tc"), integ = column(head, "integrator");
  for (std::size_t k = 1; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), head.size()) << "row " << k;
    // at Δt = t_c/20 every problem is stable and has a finite error
    if (rows[k][dto] == "0.05" && rows[k][integ] == "velocity_verlet") {
      EXPECT_EQ(rows[k][stable], "true") << rows[k][0];
      EXPECT_NE(rows[k][err], "nan") << rows[k][0];
    }
  }
  // the statistical problems: a finite error, a positive statistical band (the band of the
  // chart) and the spread against the reference's; tapping reports its wall time per tap
  const int prob = column(head, "problem"), stat = column(head, "stat_error");
  const int sd_err = column(head, "sd_error"), per_tap = column(head, "wall_per_tap_s");
  const int sw = column(head, "switches");
  ASSERT_GE(stat, 0);
  ASSERT_GE(sd_err, 0);
  ASSERT_GE(per_tap, 0);
  int tapping = 0, rfm = 0, early = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto& row = rows[k];
    if (row[prob] != "tapping" && row[prob] != "rfm_temperature") continue;
    (row[prob] == "tapping" ? tapping : rfm)++;
    if (row[sw].find("early_rest=on") != std::string::npos) ++early;
    if (row[integ] != "velocity_verlet" || row[dto] != "0.05") continue;
    EXPECT_EQ(row[stable], "true") << row[prob];
    EXPECT_TRUE(std::isfinite(std::stod(row[err]))) << row[prob];
    EXPECT_GT(std::stod(row[stat]), 0.0) << row[prob];
    EXPECT_TRUE(std::isfinite(std::stod(row[sd_err]))) << row[prob];
    if (row[prob] == "tapping") {
      EXPECT_GT(std::stod(row[per_tap]), 0.0);
    }
  }
  EXPECT_EQ(tapping, 8);
  EXPECT_EQ(rfm, 4);
  EXPECT_EQ(early, 4);
  // the stability map: one row per integrator for each of the two problems
  const auto stab = read_csv(out / "stability.csv");
  ASSERT_EQ(stab.size(), 1u + 4u);
  const int ms = column(stab[0], "max_stable_dt_over_tc");
  for (std::size_t k = 1; k < stab.size(); ++k) EXPECT_GT(std::stod(stab[k][ms]), 0.0);
  EXPECT_TRUE(fs::exists(out / "study.json"));
  // charts only where matplotlib is installed
  if (sh("/usr/bin/python3 -c 'import matplotlib'").code == 0) {
    for (const char* f :
         {"error_cost_two_disk.png", "error_cost_pile.png", "error_cost_tapping.png",
          "error_cost_tapping_sd.png", "error_cost_rfm_temperature.png",
          "error_cost_rfm_temperature_sd.png", "stability_map.png"})
      EXPECT_TRUE(fs::exists(out / f)) << f << "\n" << r.output;
  } else {
    GTEST_LOG_(INFO) << "matplotlib missing: chart check skipped";
  }
  if (!HasFailure()) fs::remove_all(out.parent_path());
}

// Gear 6 at one contact time per step: the health check stops the run, the study records it
TEST(Study, UnstableStepIsRecordedWithTheHealthMessage) {
  StudyCase c;
  c.problem = StudyProblem::TwoDisk;
  c.integrator = IntegratorKind::Gear6;
  c.dt_over_tc = 1.0;
  const StudyOutcome o = run_study_case(StudySizes{}, c);
  EXPECT_FALSE(o.stable);
  EXPECT_NE(o.note.find("dt = "), std::string::npos) << o.note;
  // and through the command: the row is there, unstable, with the message
  const fs::path dir = scratch("unstable");
  std::ofstream(dir / "u.toml") << "name = \"u\"\nproblems = [\"two_disk\"]\n[matrix]\n"
                                   "integrators = [\"gear6\"]\ndt_over_tc = [0.02, 1.0]\n";
  const Result r = sh(
      gransim("study " + (dir / "u.toml").string() + " --quiet --out " + (dir / "out").string()));
  ASSERT_EQ(r.code, 0) << r.output;
  const auto rows = read_csv(dir / "out" / "study.csv");
  ASSERT_EQ(rows.size(), 3u);
  const int stable = column(rows[0], "stable"), note = column(rows[0], "note");
  EXPECT_EQ(rows[1][stable], "true");
  EXPECT_EQ(rows[2][stable], "false");
  EXPECT_NE(rows[2][note].find("dt = "), std::string::npos) << rows[2][note];
  if (!HasFailure()) fs::remove_all(dir);
}

TEST(Study, BadStudyFileNamesFileLineAndKey) {
  const fs::path dir = scratch("bad");
  const fs::path f = dir / "bad.toml";
  std::ofstream(f) << "name = \"bad\"\nproblems = [\"two_disk\"]\n[matrix]\n"
                      "integrators = [\"gear6\"]\ndt_over_tc = [0.05]\nintegrater = 3\n";
  Result r = sh(gransim("study " + f.string() + " --out " + (dir / "o").string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml:6"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("matrix.integrater"), std::string::npos) << r.output;
  // an unknown integrator names the key and the allowed values
  std::ofstream(f) << "name = \"bad\"\nproblems = [\"two_disk\"]\n[matrix]\n"
                      "integrators = [\"leapfrog\"]\ndt_over_tc = [0.05]\n";
  r = sh(gransim("study " + f.string() + " --out " + (dir / "o").string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.toml:4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("matrix.integrators"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("velocity_verlet"), std::string::npos) << r.output;
  // a tapping table that leaves fewer than 3 taps to measure
  std::ofstream(f) << "name = \"bad\"\nproblems = [\"tapping\"]\n[matrix]\n"
                      "integrators = [\"gear6\"]\ndt_over_tc = [0.05]\n"
                      "[tapping]\ntaps = 4\ndiscard = 2\n";
  r = sh(gransim("study " + f.string() + " --out " + (dir / "o").string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("tapping.discard"), std::string::npos) << r.output;
  // a step no contact is resolved with in 10⁴ steps (10⁻³⁰⁰ t_c: "the bodies never touched")
  for (const char* at : {"[matrix]\nintegrators = [\"gear6\"]\ndt_over_tc = [1e-300]\n",
                         "reference_dt_over_tc = 1e-300\n[matrix]\nintegrators = [\"gear6\"]\n"
                         "dt_over_tc = [0.05]\n"}) {
    std::ofstream(f) << "name = \"bad\"\nproblems = [\"two_disk\"]\n" << at;
    r = sh(gransim("study " + f.string() + " --out " + (dir / "o").string()));
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("dt_over_tc"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("1e-4"), std::string::npos) << r.output;
  }
  // a missing matrix
  std::ofstream(f) << "problems = [\"pile\"]\n";
  r = sh(gransim("study " + f.string() + " --out " + (dir / "o").string()));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("matrix"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gs

// `gransim analyze` on tiny RFM runs: a 2D fluid and two 1D rings of different N are run
// through run_command, then analysed in-process (analyze_rfm_runs) and through the gransim
// binary (the dispatch in analyze.cpp). Checks: the per-run analysis files exist, the
// exponent fit across the two rings gives ζ₁ = 1 (⟨R⟩ = L′/N exactly, T.3.20) and ξ₂ is a
// finite number, and the charts are drawn when python with matplotlib is available.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "analysis/rfm_csv.hpp"
#include "app/analyze/rfm_analyze.hpp"
#include "app/run/run.hpp"
#include "app/run/run_info.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

constexpr const char* k2D = R"(
[scene]
duration = 0.03
[model]
kind = "S"
rotation = false
[[material]]
name = "glass"
eps_n = 0.6
eps_t = 0.6
mu = 0.0
[[species]]
name = "bead"
radius = 0.0015
mass = 3.53e-5
count = 200
[box]
kind = "periodic"
width = 0.06
[preparation]
placement = "uniform"
velocity_amplitude = 0.5
[drive]
kind = "random_force"
[rfm]
sample_every = 200
discard_time = 0.01
)";

constexpr const char* k1D = R"(
[scene]
duration = 0.06
[model]
kind = "S"
rotation = false
[[material]]
name = "glass"
eps_n = 0.5
eps_t = 1.0
[[species]]
name = "bead"
radius = 0.0015
mass = 3.53e-5
count = 50
[box]
kind = "ring"
reduced_length = 1.0
[preparation]
velocity_amplitude = 1.0
[drive]
kind = "random_force"
[rfm]
sample_every = 200
discard_time = 0.01
)";

struct Runs {
  fs::path root;
  Runs() {
    root = fs::temp_directory_path() / ("gs_rfm_analyze_" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root / "sizes");
    std::ofstream(root / "fluid.toml") << k2D;
    std::ofstream(root / "ring.toml") << k1D;
    run("fluid.toml", root / "fluid", {});
    run("ring.toml", root / "sizes" / "ring50", {});
    run("ring.toml", root / "sizes" / "ring100", {"species[0].count=100"});
  }
  ~Runs() { fs::remove_all(root); }
  void run(const char* scene, const fs::path& out, std::vector<std::string> sets) {
    RunOptions o;
    o.scene = (root / scene).string();
    o.out = out.string();
    o.sets = std::move(sets);
    o.quiet = true;
    ASSERT_EQ(run_command(o), 0);
  }
};

Runs& runs() {
  static Runs r;
  return r;
}

TEST(RfmAnalyze, WritesThePerRunAnalysisAndExponents) {
  const Runs& r = runs();
  EXPECT_TRUE(is_rfm_run((r.root / "fluid").string()));
  EXPECT_TRUE(is_rfm_run((r.root / "sizes").string()));  // a folder of runs
  EXPECT_FALSE(is_rfm_run(r.root.string() + "/nothing"));
  const fs::path out = r.root / "analysis";
  analyze_rfm_runs({(r.root / "fluid").string(), (r.root / "sizes").string()}, out.string(),
                   /*charts=*/false, /*quiet=*/true);
  for (const char* f : {"fluid/velocity.csv", "fluid/sk.csv", "fluid/gr.csv", "fluid/freepath.csv",
                        "fluid/temperature.csv", "fluid/moments.csv", "fluid/velocity_post.csv",
                        "ring50/gh.csv", "ring50/gh_bisection.csv", "ring100/gap_moments.csv",
                        "exponents.csv", "moments_vs_N.csv", "rfm_summary.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  // S(k) of the fluid carries the D_f fit of the k_D / L_Eff rule (T.4.5–4.9):
  // l₀ = L²/(2dN) = 3 mm, k_D = (2 − 0.72)/(8 l₀) = 53.3 1/m, L_Eff = 0.33 m > L → k′ = 2 k_D
  const rfm::CsvTable sk = rfm::read_csv(out / "fluid" / "sk.csv");
  if (sk.meta.count("k_D")) {
    EXPECT_NEAR(sk.meta.at("k_D"), 1.28 / (8 * 0.06 * 0.06 / (2 * 0.003 * 200)), 1e-9);
    EXPECT_NEAR(sk.meta.at("k_hi"), 2 * sk.meta.at("k_D"), 1e-9);
  }
  // exponents across the two rings: ζ₁ = 1 exactly (⟨R⟩ = L′/N), ξ_m finite
  const rfm::CsvTable ex = rfm::read_csv(out / "exponents.csv");
  const auto& q = ex.column.at("quantity");
  const auto& m = ex.column.at("m");
  const auto& e = ex.column.at("exponent");
  int found = 0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    EXPECT_EQ(ex.column.at("dimension")[i], 1.0);
    EXPECT_TRUE(std::isfinite(e[i]));
    if (q[i] == 1.0 && m[i] == 1.0) {
      EXPECT_NEAR(e[i], 1.0, 1e-3);
      ++found;
    }
  }
  EXPECT_EQ(found, 1);
  EXPECT_EQ(q.size(), 24u);  // ξ_m and ζ_m, m = 1…12
}

// T(t) in 50-ms blocks: every sample of rfm_series.csv in one block, the steady ones those of
// temperature.csv, with the same mean
TEST(RfmAnalyze, TemperatureBlocksHoldEverySample) {
  const Runs& r = runs();
  const fs::path out = r.root / "analysis_blocks";
  analyze_rfm_runs({(r.root / "fluid").string()}, out.string(), /*charts=*/false, /*quiet=*/true);
  const rfm::CsvTable b = rfm::read_csv(out / "fluid" / "temperature_blocks.csv");
  const rfm::CsvTable series = rfm::read_csv(r.root / "fluid" / "rfm_series.csv");
  const rfm::CsvTable temp = rfm::read_csv(r.root / "fluid" / "temperature.csv");
  double all = 0.0, steady = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < b.col("n").size(); ++i) {
    all += b.col("n")[i];
    if (b.col("steady")[i] != 0.0) {
      steady += b.col("n")[i];
      sum += b.col("n")[i] * b.col("T")[i];
    }
  }
  EXPECT_EQ(all, static_cast<double>(series.col("t").size()));
  ASSERT_EQ(steady, static_cast<double>(temp.col("T").size()));
  double direct = 0.0;
  for (double x : temp.col("T")) direct += x;
  EXPECT_NEAR(sum / steady, direct / steady, 1e-12 * std::abs(direct / steady));
  EXPECT_NEAR(b.meta.at("T_mean"), direct / steady, 1e-12 * std::abs(direct / steady));
  EXPECT_EQ(b.meta.at("block"), 0.05);
}

// the gransim binary dispatches analyze to the RFM analysis; charts when python can draw them
// (both rings, so that the across-size chart moments_vs_N.png is drawn too)
TEST(RfmAnalyze, BinaryAnalyzesAndDrawsCharts) {
  const Runs& r = runs();
  const fs::path out = r.root / "analysis_bin";
  const std::string cmd = std::string(GS_BINARY) + " analyze " + (r.root / "sizes").string() +
                          " --out " + out.string() + " -q 2>" + (r.root / "err.txt").string();
  ASSERT_EQ(std::system(cmd.c_str()), 0)
      << read_text_file((r.root / "err.txt").string()).value_or("");
  EXPECT_TRUE(fs::exists(out / "ring50" / "velocity.csv"));
  EXPECT_TRUE(fs::exists(out / "rfm_summary.json"));
  const std::string err = read_text_file((r.root / "err.txt").string()).value_or("");
  if (err.find("charts skipped") != std::string::npos)
    GTEST_SKIP() << "no python/matplotlib: " << err;
  // every chart of a ring, and the comparisons: G_h against the bisection, post-collision
  // against all velocities, moments against N with ξ_m, ζ_m (a PNG of a few kB is an empty frame)
  for (const char* f :
       {"ring50/velocity.png", "ring50/gh.png", "ring50/temperature.png", "ring50/tail_scan.png",
        "ring50/lnln.png", "ring50/freepath.png", "ring50/gh_bisection.png",
        "ring50/postcollision.png", "ring100/gh_bisection.png", "moments_vs_N.png"}) {
    std::error_code ec;
    EXPECT_TRUE(fs::exists(out / f)) << f;
    EXPECT_GT(fs::file_size(out / f, ec), 15000u) << f;
  }
}

}  // namespace
}  // namespace gs

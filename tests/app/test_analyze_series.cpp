// `gransim analyze` on plain φ series that are not gransim runs (a manifest or --series):
// every table is written and the charts that the columns allow; mistakes name the argument
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "analysis/tap_synthetic.hpp"
#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::run_binary;

class AnalyzeSeries : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gs-series-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // three exactly sampled ideal quadron gases (known answers), one file without a tap column
    QuadronGasSpec gas;
    const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
    const double xs[] = {0.8, 1.2, 1.8};
    for (int k = 0; k < 3; ++k) {
      const auto phi = quadron_gas_phi(xs[k] * scale, 400, gas, 11, static_cast<std::uint64_t>(k));
      std::ofstream f(dir_ / ("s" + std::to_string(k) + ".csv"));
      f << (k == 2 ? "phi\n" : "tap,phi\n");
      for (std::size_t i = 0; i < phi.size(); ++i)
        f << (k == 2 ? "" : std::to_string(i + 1) + ",") << phi[i] << "\n";
    }
    std::ofstream m(dir_ / "manifest.csv");
    m << "file,protocol,control,test_area\n";
    for (int k = 0; k < 3; ++k) m << "s" << k << ".csv,experiment," << 2 * k + 2 << ",0.13\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(AnalyzeSeries, AManifestOfPlainSeriesGivesEveryTable) {
  testing::Launch how;
  how.alarm_s = 120;
  const auto o = run_binary({"analyze", "--manifest", (dir_ / "manifest.csv").string(), "-q"},
                            dir_ / "log.txt", how);
  ASSERT_EQ(o.code, 0) << o.output;
  const fs::path a = dir_ / "analysis";
  for (const char* f : {"summary.csv", "series.csv", "kde.csv", "q_lines.csv", "beta.csv",
                        "beta_multi.csv", "quadron.json", "analysis.json", "runs.csv"})
    EXPECT_TRUE(fs::exists(a / f)) << f;
  // one summary row per series
  std::ifstream s(a / "summary.csv");
  int rows = 0;
  for (std::string line; std::getline(s, line);) ++rows;
  EXPECT_EQ(rows, 4);
  // the φ̄ and σ charts when matplotlib is there; the per-run charts say what they lack
  if (o.output.find("charts skipped") == std::string::npos) {
    EXPECT_TRUE(fs::exists(a / "fig5_mean_sigma_experiment.png")) << o.output;
  }
  EXPECT_EQ(o.output.find("Traceback"), std::string::npos) << o.output;
}

TEST_F(AnalyzeSeries, SeriesOnTheCommandLineAndTheirMistakes) {
  const std::string s0 = (dir_ / "s0.csv").string(), s1 = (dir_ / "s1.csv").string();
  auto o = run_binary({"analyze", "--series", "negative_g:4:" + s0, "--series", "negative_g:6:" + s1,
                       "--test-area", "0.13", "--out", (dir_ / "cli").string(), "--no-charts", "-q"},
                      dir_ / "log.txt");
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "cli" / "beta.csv"));
  // no test area
  o = run_binary({"analyze", "--series", "negative_g:4:" + s0, "--out", (dir_ / "x").string()},
                 dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("--test-area"), std::string::npos) << o.output;
  // a malformed --series, a missing file named with the manifest's line
  o = run_binary({"analyze", "--series", "negative_g" + s0, "--test-area", "0.1", "--out",
                  (dir_ / "x").string()},
                 dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("PROTOCOL:CONTROL:FILE"), std::string::npos) << o.output;
  std::ofstream(dir_ / "bad.csv") << "file,protocol,control\ns0.csv,a,1\nnope.csv,a,2\n";
  o = run_binary({"analyze", "--manifest", (dir_ / "bad.csv").string(), "--test-area", "0.1"},
                 dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("bad.csv:3"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace gs

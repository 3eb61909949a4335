// `gransim analyze` on plain φ series that are not gransim runs (a manifest or --series):
// every table is written and the charts that the columns allow; mistakes name the argument
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

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
  auto o =
      run_binary({"analyze", "--series", "negative_g:4:" + s0, "--series", "negative_g:6:" + s1,
                  "--test-area", "0.13", "--out", (dir_ / "cli").string(), "--no-charts", "-q"},
                 dir_ / "log.txt");
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "cli" / "beta.csv"));
  // no test area: the φ statistics, and a note naming --test-area
  o = run_binary(
      {"analyze", "--series", "negative_g:4:" + s0, "--out", (dir_ / "x").string(), "--no-charts"},
      dir_ / "log.txt");
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_NE(o.output.find("--test-area"), std::string::npos) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "x" / "summary.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "x" / "beta.csv"));
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

// the last two columns of summary.csv's first row: the taps dropped and whether steady
std::pair<int, int> first_cut(const fs::path& summary) {
  std::ifstream f(summary);
  std::string line;
  std::getline(f, line);
  std::getline(f, line);
  const auto last = line.rfind(',');
  const auto before = line.rfind(',', last - 1);
  return {std::stoi(line.substr(before + 1, last - before - 1)), std::stoi(line.substr(last + 1))};
}

// --discard-auto: a series that compacts over its first taps (8 spreads, e^{−tap/20}) loses
// them (the MSER-5 cut, near 58 taps), against the fixed 10 without it
TEST_F(AnalyzeSeries, DiscardAutoDropsASlowTransient) {
  std::ifstream in(dir_ / "s0.csv");
  std::vector<double> phi;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) phi.push_back(std::stod(line.substr(line.find(',') + 1)));
  double m = 0.0, v = 0.0;
  for (double x : phi) m += x / phi.size();
  for (double x : phi) v += (x - m) * (x - m) / (phi.size() - 1);
  std::ofstream out(dir_ / "slow.csv");
  out << "phi\n";
  for (std::size_t i = 0; i < phi.size(); ++i)
    out << phi[i] - 8.0 * std::sqrt(v) * std::exp(-static_cast<double>(i) / 20.0) << "\n";
  out.close();
  const std::vector<std::string> args = {"analyze",
                                         "--series",
                                         "negative_g:2:" + (dir_ / "slow.csv").string(),
                                         "--series",
                                         "negative_g:6:" + (dir_ / "s1.csv").string(),
                                         "--test-area",
                                         "0.13",
                                         "--no-charts",
                                         "-q"};
  auto with = [&](const std::string& out_dir, bool automatic) {
    std::vector<std::string> a = args;
    a.push_back("--out");
    a.push_back((dir_ / out_dir).string());
    if (automatic) a.push_back("--discard-auto");
    const auto o = run_binary(a, dir_ / "log.txt");
    EXPECT_EQ(o.code, 0) << o.output;
    return first_cut(dir_ / out_dir / "summary.csv");
  };
  EXPECT_EQ(with("fixed", false).first, 10);
  const auto [cut, steady] = with("auto", true);
  EXPECT_GE(cut, 30);
  EXPECT_LE(cut, 100);
  EXPECT_EQ(steady, 1);
}

// a stand-in `python3` in a folder of its own, for the interpreter choice
fs::path fake_python(const fs::path& dir, const std::string& body) {
  fs::create_directories(dir);
  const fs::path p = dir / "python3";
  std::ofstream(p) << "#!/bin/sh\n" << body << "\n";
  fs::permissions(p, fs::perms::owner_all);
  return dir;
}

// the charts run under `python3` on PATH when it has matplotlib, else under Debian's; a failure
// is blamed on matplotlib only when matplotlib is what is missing
TEST_F(AnalyzeSeries, ChartsUseAPythonThatHasMatplotlib) {
  if (std::system("/usr/bin/python3 -c 'import numpy, matplotlib' 2>/dev/null") != 0)
    GTEST_SKIP() << "Debian's python3 has no matplotlib here";
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "/usr/bin:/bin";
  const std::string manifest = (dir_ / "manifest.csv").string();
  testing::Launch how;
  how.alarm_s = 120;
  // the user's python3 lacks matplotlib: Debian's draws, the user's runs no script
  const fs::path bare = fake_python(dir_ / "bare", "case \"$1\" in -c) exit 1;; esac\ntouch " +
                                                       (dir_ / "bare-used").string() + "\nexit 1");
  how.env = {"PATH=" + bare.string() + ":" + path};
  auto o = run_binary({"analyze", "--manifest", manifest, "--out", (dir_ / "a1").string(), "-q"},
                      dir_ / "log.txt", how);
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "a1" / "fig5_mean_sigma_experiment.png")) << o.output;
  EXPECT_FALSE(fs::exists(dir_ / "bare-used"));
  // the user's python3 has it: it draws
  const fs::path full = fake_python(
      dir_ / "full", "touch " + (dir_ / "full-used").string() + "\nexec /usr/bin/python3 \"$@\"");
  how.env = {"PATH=" + full.string() + ":" + path};
  o = run_binary({"analyze", "--manifest", manifest, "--out", (dir_ / "a2").string(), "-q"},
                 dir_ / "log.txt", how);
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "a2" / "fig5_mean_sigma_experiment.png")) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "full-used"));
  // GS_PYTHON wins, and a python without matplotlib is named as such
  how.env = {"GS_PYTHON=" + (bare / "python3").string()};
  o = run_binary({"analyze", "--manifest", manifest, "--out", (dir_ / "a3").string(), "-q"},
                 dir_ / "log.txt", how);
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_NE(o.output.find("cannot import numpy and matplotlib"), std::string::npos) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "a3" / "summary.csv"));
  // a chart module that fails for another reason is not blamed on matplotlib
  const fs::path charts = dir_ / "python" / "gransim" / "charts";
  fs::create_directories(charts);
  std::ofstream(dir_ / "python" / "gransim" / "__init__.py") << "";
  std::ofstream(charts / "__init__.py") << "";
  std::ofstream(charts / "tapping.py") << "raise KeyError('kinetic_energy')\n";
  how.env = {"GS_PYTHON_DIR=" + (dir_ / "python").string()};
  o = run_binary({"analyze", "--manifest", manifest, "--out", (dir_ / "a4").string(), "-q"},
                 dir_ / "log.txt", how);
  EXPECT_EQ(o.code, 0) << o.output;
  EXPECT_NE(o.output.find("gransim.charts.tapping failed under"), std::string::npos) << o.output;
  EXPECT_EQ(o.output.find("matplotlib"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace gs

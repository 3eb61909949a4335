// `gransim analyze FILE[:label] ...`: an experimentalist's φ series as they are, without a
// scene, a protocol or a test area; labels never collide; mistakes name what was found
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/tap_synthetic.hpp"
#include "binary.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;
using testing::run_binary;

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

class AnalyzePlain : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gs-plain-cli-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "b");
    // two ideal quadron gases: a.csv as a comma file, b/a.csv (the same name elsewhere) as a
    // European spreadsheet writes it (';', decimal comma, capitals)
    QuadronGasSpec gas;
    const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
    for (int k = 0; k < 2; ++k) {
      const auto phi = quadron_gas_phi((1.0 + 0.6 * k) * scale, 300, gas, 5, 70 + k);
      std::ofstream f(k == 0 ? dir_ / "a.csv" : dir_ / "b" / "a.csv");
      f << (k == 0 ? "tap,phi\n" : "Tap;Phi\n");
      for (std::size_t i = 0; i < phi.size(); ++i) {
        std::string v = std::to_string(phi[i]);
        if (k == 1) v[v.find('.')] = ',';
        f << i + 1 << (k == 0 ? "," : ";") << v << "\n";
      }
    }
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// one file: its φ statistics beside it, a note that β̂ needs the test area, and not a word about
// protocols it does not have
TEST_F(AnalyzePlain, OneFileNeedsNothingElse) {
  const auto o =
      run_binary({"analyze", (dir_ / "a.csv").string(), "--no-charts"}, dir_ / "log.txt");
  ASSERT_EQ(o.code, 0) << o.output;
  const fs::path out = dir_ / "a_analysis";
  EXPECT_TRUE(fs::exists(out / "summary.csv")) << o.output;
  EXPECT_FALSE(fs::exists(out / "beta.csv"));
  EXPECT_NE(o.output.find("--test-area"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("no test area"), std::string::npos) << o.output;
  for (const char* word : {"negative", "rotating", "g_p"})
    EXPECT_EQ(o.output.find(word), std::string::npos) << word << "\n" << o.output;
  EXPECT_NE(slurp(out / "summary.csv").find("\na,,nan,300,290,"), std::string::npos)
      << slurp(out / "summary.csv");
}

// two files with labels (one of them ';'-separated): compared pairwise; the test area adds β̂.
// Without labels the two a.csv are told apart by their paths.
TEST_F(AnalyzePlain, SeveralFilesAreComparedAndNeverCollide) {
  const std::string a = (dir_ / "a.csv").string(), b = (dir_ / "b" / "a.csv").string();
  auto o = run_binary({"analyze", a + ":dry", b + ":wet", "--out", (dir_ / "two").string(),
                       "--test-area", "0.13", "--no-charts", "-q"},
                      dir_ / "log.txt");
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_NE(slurp(dir_ / "two" / "pairs.csv").find("\ndry,wet,"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir_ / "two" / "beta.csv"));
  o = run_binary({"analyze", a, b, "--out", (dir_ / "same").string(), "--no-charts", "-q"},
                 dir_ / "log.txt");
  ASSERT_EQ(o.code, 0) << o.output;
  const std::string runs = slurp(dir_ / "same" / "runs.csv");
  EXPECT_NE(runs.find("\n" + a + ","), std::string::npos) << runs;
  EXPECT_NE(runs.find("\n" + b + ","), std::string::npos) << runs;
  // --series with one protocol and control: labelled by the file as well
  o = run_binary({"analyze", "--series", "negative_g:6:" + a, "--series", "negative_g:6:" + b,
                  "--out", (dir_ / "series").string(), "--no-charts", "-q"},
                 dir_ / "log.txt");
  ASSERT_EQ(o.code, 0) << o.output;
  const std::string s = slurp(dir_ / "series" / "summary.csv");
  EXPECT_NE(s.find("\nnegative_g_6@" + a + ","), std::string::npos) << s;
  EXPECT_NE(s.find("\nnegative_g_6@" + b + ","), std::string::npos) << s;
  // several series and no --out, a missing file, files mixed with run directories
  o = run_binary({"analyze", a, b}, dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("--out"), std::string::npos) << o.output;
  o = run_binary({"analyze", (dir_ / "nope.csv").string()}, dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("nope.csv"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("no such file"), std::string::npos) << o.output;
  o = run_binary({"analyze", a, (dir_ / "b").string(), "--out", (dir_ / "x").string()},
                 dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("not both"), std::string::npos) << o.output;
}

// the charts of two labelled series: φ̄ and σ_φ per series, their densities, nothing about
// protocols or β, no traceback
TEST_F(AnalyzePlain, ChartsOfSeriesSayNothingOfProtocols) {
  if (std::system("/usr/bin/python3 -c 'import numpy, matplotlib' 2>/dev/null") != 0)
    GTEST_SKIP() << "Debian's python3 has no matplotlib here";
  testing::Launch how;
  how.alarm_s = 120;
  const auto o =
      run_binary({"analyze", (dir_ / "a.csv").string() + ":dry",
                  (dir_ / "b" / "a.csv").string() + ":wet", "--out", (dir_ / "charts").string()},
                 dir_ / "log.txt", how);
  ASSERT_EQ(o.code, 0) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "charts" / "fig5_mean_sigma_series.png")) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "charts" / "fig7a_kde_series.png")) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "charts" / "fig11_sigma_phi.png")) << o.output;
  for (const char* word : {"negative", "rotating", "Traceback", "missing", "lack"})
    EXPECT_EQ(o.output.find(word), std::string::npos) << word << "\n" << o.output;
}

// a column that is not there: the header found is shown, with its separator
TEST_F(AnalyzePlain, AMissingColumnShowsTheHeader) {
  std::ofstream(dir_ / "c.csv") << "Tap;Density\n1;0,82\n";
  const auto o = run_binary({"analyze", (dir_ / "c.csv").string()}, dir_ / "log.txt");
  EXPECT_EQ(o.code, 2);
  EXPECT_NE(o.output.find("c.csv:1"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("'Tap', 'Density'"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("';'"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace gs

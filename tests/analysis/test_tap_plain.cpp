// φ series from anywhere: the reader takes a spreadsheet's separators and capitals and shows the
// header it found when a column is missing; without a test area the analysis is the φ
// statistics, and series of unknown origin are compared with each other
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "analysis/tap_analysis.hpp"
#include "analysis/tap_synthetic.hpp"
#include "core/error.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

TapSeries parse(const std::string& text) {
  std::istringstream in(text);
  return parse_taps_csv(in, "mem.csv");
}

// the same two taps written as a European spreadsheet, a tab-separated export, numpy.savetxt
// and a bare column, each with other capitals
TEST(TapPlainCsv, SeparatorsCaseAndABareColumn) {
  for (const char* text : {"Tap;PHI;T\n1;0,82;3,5\n2;0,815;7\n", "TAP\tPhi\n1\t0.82\n2\t0.815\n",
                           "tap phi\n1 0.82\n2   0.815\n", "0.82\n0.815\n"}) {
    const TapSeries s = parse(text);
    ASSERT_EQ(s.phi.size(), 2u) << text;
    EXPECT_DOUBLE_EQ(s.phi[0], 0.82) << text;
    EXPECT_DOUBLE_EQ(s.phi[1], 0.815) << text;
    EXPECT_DOUBLE_EQ(s.tap[1], 2.0) << text;
  }
  EXPECT_DOUBLE_EQ(parse("Tap;PHI;T\n1;0,82;3,5\n").t[0], 3.5);
}

// a missing column: the message shows the header found and its separator
TEST(TapPlainCsv, AMissingColumnShowsTheHeaderFound) {
  try {
    parse("# exported\nTap;Density;Time\n1;0,82;3\n");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(e.key(), "phi");
    EXPECT_EQ(e.where(), "mem.csv:2");
    EXPECT_NE(m.find("'Tap', 'Density', 'Time'"), std::string::npos) << m;
    EXPECT_NE(m.find("';'"), std::string::npos) << m;
  }
  // a bad cell is still named by line and column
  try {
    parse("phi\n0.82\nabc\n");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "mem.csv:3");
  }
}

std::vector<TapRunInput> two_plain_series() {
  QuadronGasSpec gas;
  const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
  std::vector<TapRunInput> runs;
  for (int k = 0; k < 2; ++k) {
    TapRunInput r;
    r.label = k == 0 ? "dry" : "wet";
    r.control = std::nan("");  // an experiment's series: no protocol, no control value
    r.series = quadron_gas_taps((1.0 + 0.5 * k) * scale, 300, gas, 3, 40 + k);
    runs.push_back(r);
  }
  return runs;
}

// analysis.json is JSON whatever the labels hold: a quote is escaped, a byte that is not UTF-8
// is written as U+FFFD, a missing value is null and a whole one an integer
TEST(TapPlainAnalysis, AnalysisJsonReadsBackWithAnyLabel) {
  auto runs = two_plain_series();
  runs[0].label = "dry \"A\"";
  runs[1].label = "wet\xff";
  TapAnalysisOptions o;
  const TapAnalysisResult r = run_tap_analysis(runs, o);
  const fs::path dir = fs::temp_directory_path() / ("gs-plain-json-" + std::to_string(::getpid()));
  write_tap_analysis(r, runs, o, dir.string());
  std::ifstream a(dir / "analysis.json");
  const nlohmann::json j = nlohmann::json::parse(a, nullptr, false);
  ASSERT_FALSE(j.is_discarded());
  ASSERT_EQ(j.at("runs").size(), 2u);
  EXPECT_EQ(j.at("runs")[0].at("label"), "dry \"A\"");
  EXPECT_EQ(j.at("runs")[1].at("label"), "wet\xef\xbf\xbd");
  EXPECT_TRUE(j.at("runs")[0].at("control").is_null());
  EXPECT_TRUE(j.at("test_area").is_null());
  EXPECT_TRUE(j.at("runs")[0].at("n_used").is_number_integer());
  EXPECT_EQ(j.at("runs")[0].at("n_used"), r.runs[0].n_used);
  EXPECT_EQ(j.at("runs")[0].at("phi_mean").get<double>(), r.runs[0].phi_mean);
  EXPECT_EQ(j.at("files")[0], "summary.csv");
  fs::remove_all(dir);
}

// without the test area: per-run statistics and the pair test, no β̂ or quadron fit, and a note
// saying why; the files are those of the φ statistics
TEST(TapPlainAnalysis, NoTestAreaGivesThePhiStatisticsOnly) {
  const auto runs = two_plain_series();
  TapAnalysisOptions o;
  ASSERT_EQ(o.test_area, 0.0);  // not known unless given
  const TapAnalysisResult r = run_tap_analysis(runs, o);
  ASSERT_EQ(r.runs.size(), 2u);
  EXPECT_TRUE(r.beta.empty());
  EXPECT_TRUE(r.quadron.empty());
  EXPECT_TRUE(r.multi.chain.empty());
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("no test area"), std::string::npos);
  // unknown origin: the two series are compared, and they differ (β differs by half)
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_LT(r.pairs[0].test.p_mean, 1e-3);
  const fs::path dir = fs::temp_directory_path() / ("gs-plain-" + std::to_string(::getpid()));
  write_tap_analysis(r, runs, o, dir.string());
  for (const char* f : {"summary.csv", "series.csv", "kde.csv", "pairs.csv", "analysis.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  for (const char* f : {"beta.csv", "q_lines.csv", "quadron.json", "beta_multi.csv"})
    EXPECT_FALSE(fs::exists(dir / f)) << f;
  std::ifstream a(dir / "analysis.json");
  const std::string json((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"test_area\": null"), std::string::npos) << json;
  EXPECT_EQ(json.find("beta.csv"), std::string::npos) << json;
  fs::remove_all(dir);
  // with it, β̂ is there and no such note
  o.test_area = 0.13;
  const TapAnalysisResult b = run_tap_analysis(runs, o);
  EXPECT_EQ(b.beta.size(), 2u);
  EXPECT_TRUE(b.beta[1].valid);
  for (const auto& n : b.notes) EXPECT_EQ(n.find("no test area"), std::string::npos) << n;
  // beta_cov.csv: a square matrix named by estimate and run, its joint diagonal the errors²
  write_tap_analysis(b, runs, o, dir.string());
  std::ifstream cf(dir / "beta_cov.csv");
  std::string header, line;
  std::getline(cf, header);
  EXPECT_EQ(header,
            "quantity,joint:dry,joint:wet,direct:dry:dry,direct:dry:wet,direct:wet:dry,"
            "direct:wet:wet");
  std::getline(cf, line);
  std::getline(cf, line);  // joint:wet
  ASSERT_EQ(line.rfind("joint:wet,", 0), 0u) << line;
  const double c = std::stod(line.substr(line.find(',', line.find(',') + 1) + 1));
  EXPECT_NEAR(c, b.multi.joint[1].dbeta_err * b.multi.joint[1].dbeta_err, 1e-9 * c);
  fs::remove_all(dir);
  o.test_area = std::nan("");
  EXPECT_THROW(run_tap_analysis(runs, o), InputError);
}

}  // namespace
}  // namespace gs

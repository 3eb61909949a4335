// the tapping analysis end to end on an exactly sampled ideal quadron gas (known β, a, ln Z),
// and the taps.csv reader's errors
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/tap_analysis.hpp"
#include "analysis/tap_synthetic.hpp"
#include "core/error.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// the study: two protocols over a range of β of the synthetic gas (x = βΔ = 0.4…2.6)
struct Study {
  QuadronGasSpec gas;
  std::vector<TapRunInput> runs;
  std::vector<double> beta;  ///< true β of each run, 1/m²
  TapAnalysisOptions opts;

  Study() {
    gas.refresh = 0.5;     // τ_int = (2 − p)/(2p) = 1.5 taps
    gas.start_fill = 0.9;  // a loose start: the transient the analysis discards
    const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();  // β per unit x
    auto add = [&](const std::string& protocol, double control, double x, std::uint64_t stream) {
      TapRunInput r;
      r.protocol = protocol;
      r.control = control;
      r.series = quadron_gas_taps(x * scale, 3000, gas, 4711, stream);
      runs.push_back(r);
      beta.push_back(x * scale);
    };
    add("negative_g", 6, 1.4, 1);
    add("negative_g", 10, 1.0, 2);
    add("negative_g", 14, 0.7, 3);
    add("negative_g", 20, 0.5, 4);
    add("negative_g", 28, 0.9, 5);
    add("rotating_g", 0.5, 2.6, 6);
    add("rotating_g", 0.75, 1.9, 7);
    add("rotating_g", 1.25, 1.2, 8);
    add("rotating_g", 2.0, 1.6, 9);
    // V_T such that V_g = V_T φ̄_ref is the gas' grain volume
    opts.test_area = gas.v_g / quadron_phi(beta[0], quadron_gas_a(gas), gas.limits);
    opts.bootstrap = 20;  // the multiple-histogram errors are tested in test_multi_hist.cpp
  }
};

TEST(TapAnalysis, SyntheticStudyRecoversTheGas) {
  const Study st;
  const TapAnalysisResult r = run_tap_analysis(st.runs, st.opts);
  const double a = quadron_gas_a(st.gas);
  const auto& lim = st.gas.limits;
  ASSERT_EQ(r.runs.size(), st.runs.size());
  EXPECT_EQ(r.ref, 0);
  EXPECT_EQ(r.ref2, 1);  // next run of the reference's protocol
  EXPECT_NEAR(r.v_g, st.gas.v_g, 1e-3 * st.gas.v_g);
  const double lz_ref = quadron_lnz(st.beta[0], a, st.gas.v_g, lim);
  for (std::size_t i = 0; i < r.runs.size(); ++i) {
    const auto& s = r.runs[i];
    const auto& b = r.beta[i];
    EXPECT_EQ(s.n_used, 2990);
    // φ̄ (P.26) within 3 standard errors (τ-corrected); E[V_g/V] − V_g/⟨V⟩ ≈ 1e-5 ≪ the error
    EXPECT_NEAR(s.phi_mean, quadron_phi(st.beta[i], a, lim), 3.0 * s.phi_err) << s.label;
    // σ_φ (P.17 with P.26) inside its τ-corrected chi-square interval widened to ≈ 3σ
    const double sp = quadron_sigma_phi(st.beta[i], a, st.gas.v_g, lim);
    const double half = 0.5 * (s.sigma_ci_tau.hi - s.sigma_ci_tau.lo);
    EXPECT_NEAR(s.sigma, sp, 1.5 * half) << s.label;
    // τ_int = 1.5 taps for refresh 1/2, within 3 of Sokal's errors
    EXPECT_NEAR(s.tau.tau_int, 1.5, 3.0 * s.tau.tau_err) << s.label;
    // halves of 36 cells each: σ ratio √2 (σ of a ratio of stds ≈ √2/√n_eff ≈ 3.5 %)
    ASSERT_TRUE(s.has_halves);
    EXPECT_NEAR(s.sigma_left / s.sigma, std::sqrt(2.0), 0.12) << s.label;
    EXPECT_NEAR(s.sigma_right / s.sigma, std::sqrt(2.0), 0.12) << s.label;
    // β̂ and Δln Z against the reference (P.39, P.40, and P.21 for ln Z) within 3σ
    ASSERT_TRUE(b.valid) << s.label << ": " << b.fit.note;
    if (static_cast<int>(i) == r.ref) continue;
    EXPECT_NEAR(b.dbeta, st.beta[i] - st.beta[0], 3.0 * b.dbeta_err) << s.label;
    const double dlnz = quadron_lnz(st.beta[i], a, st.gas.v_g, lim) - lz_ref;
    EXPECT_NEAR(b.dlnz, dlnz, 3.0 * b.dlnz_err) << s.label;
  }
  // the two references differ by the constant β_ref2 − β_ref, within the error of β̂(ref2)
  EXPECT_NEAR(r.ref_offset, st.beta[1] - st.beta[0], 3.0 * r.beta[1].dbeta_err);

  // the quadron fit over all runs recovers a = N z̄/V_g and β₀ = β_ref within 3σ
  ASSERT_TRUE(r.quadron.count("all"));
  const QuadronFit& f = r.quadron.at("all");
  ASSERT_TRUE(f.converged) << f.note;
  std::printf(
      "tap study: a = %.1f +- %.1f (true %.2f), beta0 = %.0f +- %.0f (true %.0f), "
      "chi2/dof = %.1f/%d\n",
      f.a, f.a_err, a, f.beta0, f.beta0_err, st.beta[0], f.chi2, f.dof);
  EXPECT_NEAR(f.a, a, 3.0 * f.a_err);
  EXPECT_NEAR(f.beta0, st.beta[0], 3.0 * f.beta0_err);
  // each protocol alone: fitted too (4–5 points), consistent with the truth
  for (const char* p : {"negative_g", "rotating_g"}) {
    ASSERT_TRUE(r.quadron.count(p)) << p;
    const QuadronFit& fp = r.quadron.at(p);
    EXPECT_TRUE(fp.converged) << p << ": " << fp.note;
    EXPECT_NEAR(fp.a, a, 3.0 * fp.a_err) << p;
  }
}

// the files the charts read: present, with their headers and one row per run and reference
// the progress the analysis reports: every step once, in order, to a total known from the start
TEST(TapAnalysis, ReportsEveryStepToAKnownTotal) {
  Study st;
  std::vector<double> done, totals;
  st.opts.progress = [&](double d, double t) {
    done.push_back(d);
    totals.push_back(t);
  };
  const TapAnalysisResult r = run_tap_analysis(st.runs, st.opts);
  ASSERT_FALSE(done.empty());
  // per run: statistics and KDEs; the pair tests; two reference fits; the joint fit and its
  // bootstrap replicas
  const double total = 2.0 * st.runs.size() + r.pairs.size() + 2.0 + 1.0 + st.opts.bootstrap;
  for (std::size_t i = 0; i < done.size(); ++i) {
    EXPECT_EQ(done[i], static_cast<double>(i + 1));
    EXPECT_EQ(totals[i], total);
  }
  EXPECT_EQ(done.back(), total);
}

TEST(TapAnalysis, WritesTheOutputFiles) {
  const Study st;
  const fs::path out = fs::temp_directory_path() / "gs_test_tap_analysis";
  fs::remove_all(out);
  analyze_tapping(st.runs, st.opts, out.string());
  std::printf("tap study written to %s\n", out.c_str());
  auto lines = [&](const char* name) {
    std::ifstream f(out / name);
    std::vector<std::string> v;
    for (std::string l; std::getline(f, l);) v.push_back(l);
    return v;
  };
  const auto summary = lines("summary.csv");
  ASSERT_EQ(summary.size(), 1 + st.runs.size());
  EXPECT_EQ(summary[0].rfind("label,protocol,control,n_total,n_used,phi_mean", 0), 0u);
  EXPECT_EQ(summary[1].rfind("negative_g_6,negative_g,6,3000,2990,", 0), 0u);
  const auto beta = lines("beta.csv");
  EXPECT_EQ(beta.size(), 1 + 2 * st.runs.size());  // two references
  EXPECT_EQ(lines("kde.csv").size(), 1 + st.runs.size() * st.opts.kde_points);
  EXPECT_EQ(lines("series.csv").size(), 1 + st.runs.size() * 3000);
  EXPECT_GT(lines("q_lines.csv").size(), 2 * st.runs.size());
  for (const char* j : {"quadron.json", "analysis.json"}) {
    const auto l = lines(j);
    ASSERT_FALSE(l.empty()) << j;
    EXPECT_EQ(l.front(), "{");
    EXPECT_EQ(l.back(), "}");
  }
  std::string q;
  for (const auto& l : lines("quadron.json")) q += l;
  EXPECT_NE(q.find("\"all\""), std::string::npos);
  EXPECT_NE(q.find("\"curve\""), std::string::npos);
}

// runs at the same protocol and control value are compared pairwise: two independent series of
// the same gas agree, a series at another compactivity (φ̄ shifted by several errors) does not
TEST(TapAnalysis, ComparesRunsAtTheSameControlValue) {
  QuadronGasSpec gas;
  gas.refresh = 0.5;  // correlated taps: τ_int = 1.5
  const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
  std::vector<TapRunInput> runs;
  for (int k = 0; k < 3; ++k) {
    TapRunInput r;
    r.label = "run" + std::to_string(k);
    r.protocol = "negative_g";
    r.control = 6;
    r.series = quadron_gas_taps((k == 2 ? 1.35 : 1.2) * scale, 400, gas, 9, 100 + k);
    runs.push_back(r);
  }
  TapRunInput other = runs[0];  // another control value: never paired
  other.label = "other";
  other.control = 8;
  runs.push_back(other);
  const TapAnalysisResult r = run_tap_analysis(runs, TapAnalysisOptions{});
  ASSERT_EQ(r.pairs.size(), 3u);  // (0,1), (0,2), (1,2)
  EXPECT_EQ(r.pairs[0].a, 0);
  EXPECT_EQ(r.pairs[0].b, 1);
  EXPECT_GT(r.pairs[0].test.p_mean, 0.001);  // same gas
  EXPECT_GT(r.pairs[0].test.ks_p, 0.001);
  EXPECT_GT(r.pairs[0].test.n_eff_a, 90);  // 390 taps / (2 τ_int ≈ 3)
  EXPECT_LT(r.pairs[0].test.n_eff_a, 200);
  EXPECT_LT(r.pairs[1].test.p_mean, 1e-4);    // another β: φ̄ differs
  EXPECT_GT(r.pairs[1].test.mean_diff, 0.0);  // larger β → denser
}

// with discard_auto each run drops its own transient: a run that compacts over its first 80
// taps (φ rising by 8 spreads, e^{−tap/20}) loses them and keeps its steady mean, a stationary
// run keeps all but the fixed 10; without it both drop 10 and the first mean is biased low
TEST(TapAnalysis, DiscardAutoDropsEachRunsOwnTransient) {
  QuadronGasSpec gas;
  const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
  std::vector<TapRunInput> runs;
  for (int k = 0; k < 2; ++k) {
    TapRunInput r;
    r.protocol = "negative_g";
    r.control = 2 + 4 * k;
    r.series = quadron_gas_taps(1.2 * scale, 250, gas, 7, 300 + k);
    runs.push_back(r);
  }
  const TapRunSummary plain = run_tap_analysis(runs, TapAnalysisOptions{}).runs[0];
  const double spread = plain.sigma;
  for (std::size_t i = 0; i < runs[0].series.phi.size(); ++i)
    runs[0].series.phi[i] -= 8.0 * spread * std::exp(-static_cast<double>(i) / 20.0);
  TapAnalysisOptions o;
  const TapAnalysisResult fixed = run_tap_analysis(runs, o);
  EXPECT_EQ(fixed.runs[0].discard, 10);
  EXPECT_EQ(fixed.runs[1].discard, 10);
  EXPECT_LT(fixed.runs[0].phi_mean, plain.phi_mean - 2.0 * plain.phi_err);
  o.discard_auto = true;
  const TapAnalysisResult cut = run_tap_analysis(runs, o);
  // the bias left falls below the batch means' noise where 8σ e^{−d/20} ≈ σ/√5: d ≈ 58
  EXPECT_GE(cut.runs[0].discard, 30);  // the first 1.5 decay lengths (bias > 1.8σ) go
  EXPECT_LE(cut.runs[0].discard, 100);
  EXPECT_EQ(cut.runs[0].n_used, 250 - cut.runs[0].discard);
  EXPECT_NEAR(cut.runs[0].phi_mean, plain.phi_mean, 3.0 * plain.phi_err);
  EXPECT_TRUE(cut.runs[0].steady);
  EXPECT_LT(cut.runs[1].discard, 40);
  EXPECT_GE(cut.runs[1].discard, 10);
}

// the default reference is the paper's (negative g, g_p nearest 6), wherever it is listed;
// an explicit label overrides it, and an unknown label is an input error
TEST(TapAnalysis, ReferenceSelection) {
  QuadronGasSpec gas;
  const double scale = quadron_gas_a(gas) / gas.limits.delta_inv();
  std::vector<TapRunInput> runs;
  const struct {
    const char* p;
    double c;
    double x;
  } spec[] = {{"rotating_g", 0.5, 1.2},
              {"negative_g", 10, 1.1},
              {"negative_g", 5, 1.3},
              {"negative_g", 8, 1.2}};
  std::uint64_t k = 0;
  for (const auto& s : spec) {
    TapRunInput r;
    r.protocol = s.p;
    r.control = s.c;
    r.series = quadron_gas_taps(s.x * scale, 300, gas, 5, ++k);
    runs.push_back(r);
  }
  TapAnalysisOptions o;
  const TapAnalysisResult r = run_tap_analysis(runs, o);
  EXPECT_EQ(r.runs[r.ref].label, "negative_g_5");   // |5 − 6| < |8 − 6|
  EXPECT_EQ(r.runs[r.ref2].label, "negative_g_8");  // the next negative_g run after it
  o.reference = "rotating_g_0.5";
  EXPECT_EQ(run_tap_analysis(runs, o).ref, 0);
  o.reference = "nope";
  EXPECT_THROW(run_tap_analysis(runs, o), InputError);
}

TEST(TapCsv, ReadsColumnsByName) {
  std::istringstream in(
      "# written by a test\n"
      "t,phi_right,tap,extra,phi,phi_left\n"
      "3.0,0.81,1,x,0.82,0.83\n"
      "\n"
      "6.0, 0.80 ,2,y,0.815,0.825\n");
  const TapSeries s = parse_taps_csv(in, "mem.csv");
  ASSERT_EQ(s.phi.size(), 2u);
  EXPECT_DOUBLE_EQ(s.tap[1], 2.0);
  EXPECT_DOUBLE_EQ(s.t[1], 6.0);
  EXPECT_DOUBLE_EQ(s.phi[1], 0.815);
  EXPECT_DOUBLE_EQ(s.phi_left[0], 0.83);
  EXPECT_DOUBLE_EQ(s.phi_right[1], 0.80);
}

TEST(TapCsv, ErrorsNameFileLineAndColumn) {
  // a missing required column names the column and the file
  std::istringstream no_phi("tap,t,phi_left\n1,0.0,0.8\n");
  try {
    parse_taps_csv(no_phi, "runs/a/taps.csv");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "phi");
    EXPECT_NE(std::string(e.what()).find("runs/a/taps.csv"), std::string::npos) << e.what();
  }
  // a bad number names the line
  std::istringstream bad("tap,phi\n1,0.82\n2,abc\n");
  try {
    parse_taps_csv(bad, "b.csv");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "b.csv:3");
    EXPECT_EQ(e.key(), "phi");
  }
  // an unreadable file names the path
  try {
    read_taps_csv("/nonexistent/dir/taps.csv");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "/nonexistent/dir/taps.csv");
  }
}

TEST(TapCsv, LoadsARunFromAFile) {
  const fs::path p = fs::temp_directory_path() / "gs_test_taps.csv";
  {
    std::ofstream f(p);
    f << "tap,t,phi,phi_left,phi_right\n";
    for (int i = 1; i <= 40; ++i)
      f << i << ',' << 3.0 * i << ',' << 0.82 + 1e-4 * (i % 7) << ",0.82,0.82\n";
  }
  const TapRunInput r = load_tap_run(p.string(), "rotating_g", 0.75);
  EXPECT_EQ(tap_run_label(r), "rotating_g_0.75");
  EXPECT_EQ(r.series.phi.size(), 40u);
  EXPECT_EQ(r.series.source, p.string());
  // too few taps after the transient is an input error, not a crash
  TapAnalysisOptions o;
  o.discard = 30;
  EXPECT_THROW(run_tap_analysis({r}, o), InputError);
  fs::remove(p);
}

// a spreadsheet's byte-order mark is not part of the first column; taps must count up
TEST(TapCsv, ByteOrderMarkAndTapOrder) {
  std::istringstream bom("\xEF\xBB\xBFtap,phi\n1,0.82\n2,0.83\n");
  EXPECT_EQ(parse_taps_csv(bom, "bom.csv").phi.size(), 2u);
  for (const char* text : {"tap,phi\n1,0.82\n1,0.83\n", "tap,phi\n2,0.82\n1,0.83\n"}) {
    std::istringstream in(text);
    try {
      parse_taps_csv(in, "t.csv");
      FAIL() << "no exception for " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "t.csv:3");
      EXPECT_EQ(e.key(), "tap");
    }
  }
}

// a tap number is a whole count (the fuzzer's 2·10⁵⁷ once overflowed a message's integer)
TEST(TapCsv, TapNumbersAreWholeCounts) {
  for (const char* text : {"tap,phi\n1,0.82\n2.5,0.83\n", "tap,phi\n1,0.82\n2e57,0.83\n",
                           "tap,phi\n1,0.82\n-3,0.83\n"}) {
    std::istringstream in(text);
    try {
      parse_taps_csv(in, "t.csv");
      FAIL() << "no exception for " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where(), "t.csv:3");
      EXPECT_EQ(e.key(), "tap");
    }
  }
  std::istringstream ok("tap,phi\n0,0.82\n1,0.83\n");
  EXPECT_EQ(parse_taps_csv(ok, "ok.csv").phi.size(), 2u);
}

}  // namespace
}  // namespace gs

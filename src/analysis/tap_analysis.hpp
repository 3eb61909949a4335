// the tapping study's analysis (docs/physics.md §2.6; paper section V): per-run statistics of φ,
// kernel density estimates, overlapping histograms against a chosen reference run, the ideal
// quadron fit over all runs and per protocol, written as CSV and JSON files for the charts
// (gransim.charts.tapping).
#pragma once
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "analysis/kde.hpp"
#include "analysis/multi_hist.hpp"
#include "analysis/overlap_hist.hpp"
#include "analysis/quadron.hpp"
#include "analysis/stats.hpp"
#include "analysis/two_sample.hpp"

namespace gs {

/// the per-tap series of one run, read from taps.csv by column name
struct TapSeries {
  std::string source;             ///< where it came from (file path), for messages
  std::vector<double> tap;        ///< tap number, dimensionless
  std::vector<double> t;          ///< time of the measurement, s (empty when the column is absent)
  std::vector<double> phi;        ///< volume fraction of the test rectangle, dimensionless
  std::vector<double> phi_left;   ///< φ of its left half (empty when absent)
  std::vector<double> phi_right;  ///< φ of its right half (empty when absent)
};

/// parse taps.csv text: a header row naming the columns (in any case), then one row per tap.
/// Required column: phi; optional: tap (else the rows are taps 1, 2, …; given, it must
/// increase), t, phi_left, phi_right; other columns are ignored. Cells are separated by commas,
/// else by the header's ';' or tab (a decimal comma is then read as a point), else by blanks;
/// a single column of numbers without a header is φ. Lines that are blank or start with '#' are
/// skipped. Throws InputError naming source:line and column; a missing column's message shows
/// the header found.
TapSeries parse_taps_csv(std::istream& in, const std::string& source);
/// read taps.csv from a file; throws InputError when the file cannot be read
TapSeries read_taps_csv(const std::string& path);

/// one run of the study: a protocol at one value of its control parameter
struct TapRunInput {
  std::string label;     ///< unique name; empty: "<protocol>_<control>"
  std::string protocol;  ///< "negative_g", "rotating_g", …; "" for a series of unknown origin
  double control = 0.0;  ///< g_p (in units of g) for negative_g, f (Hz) for rotating_g; NaN
                         ///< when unknown
  TapSeries series;      ///< the measurements
};

/// a run read from its taps.csv
TapRunInput load_tap_run(const std::string& path, const std::string& protocol, double control,
                         const std::string& label = "");

/// choices of the analysis
struct TapAnalysisOptions {
  int discard = 10;           ///< transient taps dropped from the start of each run
  bool discard_auto = false;  ///< per run, drop the larger of `discard` and the MSER-5 cut
                              ///< (mser_truncation): a slow transient is left out whole
  double level = 0.95;        ///< confidence level of the intervals
  double alpha = 0.05;        ///< significance of the normality test
  double test_area = 0.0;     ///< area V_T of the test rectangle, m² (V_g = V_T φ̄_ref);
                              ///< 0: not known, φ statistics only (no β̂, no quadron fit)
  std::string reference;      ///< label of the reference run; empty: the paper's choice, the
                              ///< negative_g run with g_p nearest 6, else the first run
  std::string reference2;     ///< second reference; empty: the next run of the reference's
                              ///< protocol (none if it has no other run)
  OverlapOptions overlap;     ///< density method, bins, 5 % threshold
  int kde_points = 200;       ///< grid points of each written KDE
  QuadronParams quadron;      ///< φ_rlp, φ_rcp of (P.26)
  int bootstrap = 100;        ///< bootstrap replicas of the multiple-histogram errors
  /// told (done, total) as the steps of the analysis finish: each run's statistics, each pair
  /// test, each run's KDEs, each β̂ fit against a reference, the joint fit and each bootstrap
  /// replica; total is known from the start
  std::function<void(double done, double total)> progress;
};

/// statistics of one run (after the transient)
struct TapRunSummary {
  std::string label;         ///< run label
  std::string protocol;      ///< protocol name
  double control = 0.0;      ///< control parameter (g_p or f, Hz)
  int n_total = 0;           ///< taps in the file
  int n_used = 0;            ///< taps after the transient
  int discard = 0;           ///< taps dropped as the transient
  bool steady = true;        ///< false: MSER found no steady part (discard_auto only)
  double phi_mean = 0.0;     ///< φ̄, dimensionless
  double phi_err = 0.0;      ///< standard error of φ̄ with τ_int: s √(2τ_int/n)
  Interval phi_mean_ci;      ///< CI of φ̄ treating taps as independent
  Interval phi_mean_ci_tau;  ///< CI of φ̄ with n_eff = n/(2τ_int)
  double sigma = 0.0;        ///< σ_φ (n − 1), dimensionless
  Interval sigma_ci;         ///< chi-square CI of σ_φ, independent taps
  Interval sigma_ci_tau;     ///< chi-square CI of σ_φ with n_eff
  AutocorrTime tau;          ///< integrated autocorrelation time, taps
  NormalityTest normality;   ///< chi-square test of normality
  bool has_halves = false;   ///< φ_left and φ_right were present
  double mean_left = 0.0;    ///< φ̄ of the left half
  double mean_right = 0.0;   ///< φ̄ of the right half
  double sigma_left = 0.0;   ///< σ_φ of the left half
  double sigma_right = 0.0;  ///< σ_φ of the right half
};

/// two runs of one protocol at one control value (e.g. fixed-period against early-rest
/// relaxation, or two integrators): are their φ distributions the same?
struct TapPairTest {
  int a = 0, b = 0;    ///< run indices
  TwoSampleTest test;  ///< means (Welch), spreads (F), distributions (KS), with n_eff
};

/// everything the analysis computes
struct TapAnalysisResult {
  std::vector<TapRunSummary> runs;                    ///< per-run statistics, input order
  std::vector<KdeCurve> kde_normal;                   ///< per-run KDE, normal kernel (Silverman h)
  std::vector<std::vector<double>> kde_epanechnikov;  ///< same grid, Epanechnikov kernel with
                                                      ///< the equivalent bandwidth
  std::vector<std::vector<double>> kde_box;           ///< same grid, box kernel, equivalent h
  int ref = 0;                                        ///< index of the reference run
  int ref2 = -1;                              ///< index of the second reference (−1: none)
  double v_g = 0.0;                           ///< V_g = V_T φ̄_ref, m²
  std::vector<BetaEstimate> beta;             ///< per run against the reference
  std::vector<BetaEstimate> beta2;            ///< per run against the second reference
  double ref_offset = 0.0;                    ///< weighted mean of β̂(ref) − β̂(ref2), 1/m²
  double ref_offset_err = 0.0;                ///< its standard error, 1/m²
  double ref_offset_chi2 = 0.0;               ///< χ² of "the difference is constant"
  int ref_offset_dof = 0;                     ///< its degrees of freedom
  MultiHistResult multi;                      ///< β̂ through neighbours: chain and joint fit
                                              ///< (runs that do not overlap the reference too)
  std::map<std::string, QuadronFit> quadron;  ///< "all" and each protocol (direct β̂), and
                                              ///< "joint" (every run, β̂ of the joint fit)
  std::vector<TapPairTest> pairs;             ///< every pair at the same protocol and control
                                              ///< (series without a protocol: every pair)
  std::vector<std::string> notes;             ///< what was skipped and why
};

/// compute the analysis (no files). Without a test area (opts.test_area ≤ 0) only the φ
/// statistics, KDEs and pair tests are computed and a note says why β̂ and the quadron fit are
/// absent. Throws InputError for unusable input (no runs, too few taps after the transient, an
/// unknown reference label, a non-finite test area).
TapAnalysisResult run_tap_analysis(const std::vector<TapRunInput>& runs,
                                   const TapAnalysisOptions& opts);
/// write summary.csv, series.csv, kde.csv, q_lines.csv, beta.csv, quadron.json and
/// analysis.json into out_dir (created if needed)
void write_tap_analysis(const TapAnalysisResult& r, const std::vector<TapRunInput>& runs,
                        const TapAnalysisOptions& opts, const std::string& out_dir);
/// both of the above
void analyze_tapping(const std::vector<TapRunInput>& runs, const TapAnalysisOptions& opts,
                     const std::string& out_dir);

/// a run's label as used in the files
std::string tap_run_label(const TapRunInput& run);

}  // namespace gs

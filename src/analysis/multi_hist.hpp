// β and ln Z of many tapping runs at once, also for runs whose φ distributions do not overlap
// the reference (paper section V, P.39 extended). With a few hundred taps per control value
// neighbouring distributions overlap but distant ones do not, so the single-reference fit
// leaves them out. Two estimators reach them through their neighbours:
// - the chain: overlapping-histogram fits between neighbours in φ̄, summed along the chain;
// - the joint multiple-histogram fit (Ferrenberg–Swendsen / WHAM with unknown β): on common
//   the pooled values of x = 1/φ every run's counts are Poisson with mean
//   n_k g_j exp(−b_k x_j)/Z_k, one density of states g for all runs, b_k = β_k V_g. With g
//   profiled out the likelihood is a convex function of (ln Z_k, b_k) (as in MBAR), minimised
//   by Newton's method. It is all but unbinned: values closer than a hundredth of the narrowest
//   run's spread share a cell at their mean, so no run's tilt changes much across one (the
//   relative bias of b is ≈ 10⁻⁵) while the cost of each Newton step is set by the cells, not
//   by the number of taps. Runs count as linked when each has
//   at least 3 values inside the other's range.
// Errors of both come from a moving-block bootstrap over taps (blocks of ≈ 2τ_int taps keep
// the serial correlation), with the binning held fixed.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/overlap_hist.hpp"

namespace gs {

/// choices of the multiple-run estimators
struct MultiHistOptions {
  int chain_bins_per_scott = 4;   ///< chain: bins per Scott width of the pair (finer bins keep
                                  ///< the tilt across one bin small, which biases the slope)
  int bootstrap = 100;            ///< bootstrap replicas for the errors (0: none, errors NaN)
  std::vector<double> tau_int;    ///< per run, taps; blocks of max(1, round(2τ_int)) (empty: 1)
  std::uint64_t seed = 20150827;  ///< seed of the bootstrap draws
  int max_iterations = 20000;     ///< joint fit: alternations before it gives up
  double tolerance = 1e-10;       ///< joint fit: largest change of b_k (1/(units of x)) to stop
  OverlapOptions overlap;         ///< the pairwise fits of the chain
  std::function<void()> step;     ///< called after the fit and after each bootstrap replica
  /// runs whose direct β̂ of every run (overlapping histograms against that run alone) the
  /// bootstrap refits too, for their covariance with the joint fit's
  std::vector<int> direct_refs;
};

/// one run's estimate relative to the reference
struct MultiBeta {
  bool valid = false;      ///< false when the run is not connected to the reference
  double dbeta = 0.0;      ///< β − β_ref, 1/m²
  double dbeta_err = 0.0;  ///< bootstrap standard error, 1/m² (NaN without bootstrap)
  double dlnz = 0.0;       ///< ln Z − ln Z_ref, dimensionless
  double dlnz_err = 0.0;   ///< bootstrap standard error (NaN without bootstrap)
};

/// both estimators for every run
struct MultiHistResult {
  std::vector<int> order;           ///< run indices by increasing φ̄ (the chain)
  std::vector<BetaEstimate> links;  ///< links[i]: run order[i+1] against run order[i]
  std::vector<MultiBeta> chain;     ///< per run (input order), summed along the chain
  std::vector<MultiBeta> joint;     ///< per run (input order), the joint fit
  bool joint_converged = false;     ///< the joint fit met its tolerance
  int joint_iterations = 0;         ///< alternations it took
  int values = 0;                   ///< cells of x in the joint fit (the pooled values, merged
                                    ///< within a hundredth of the narrowest run's σ)
  std::int64_t terms = 0;           ///< work of the joint fits, bootstrap included: Σ over
                                    ///< objective evaluations of cells × runs
  int replicas = 0;                 ///< bootstrap replicas that were used
  /// bootstrap covariance of the β̂ (1/m⁴) from the same replicas as the errors: index
  /// b·K + k is run k's β̂ of block b, block 0 the joint fit, block 1 + i the direct β̂ against
  /// direct_refs[i]; NaN where fewer than half the replicas reached both runs; a reference's
  /// own β̂ is 0 (row and column 0). Its joint diagonal is joint[k].dbeta_err².
  std::vector<std::vector<double>> cov;
  std::vector<std::string> notes;  ///< runs left out and why
};

/// both estimates of β − β_ref and ln Z − ln Z_ref for every run; phi[k] are run k's taps
/// (after the transient), v_g the grain volume of the test region (m²). Throws InputError when
/// there are fewer than two runs, a run has fewer than 3 values, or a value is not in (0, 1].
MultiHistResult multi_histogram_beta(const std::vector<std::vector<double>>& phi, int ref,
                                     double v_g, const MultiHistOptions& opts = {});

/// the joint fit alone on given counts: counts[k][j] of run k at the value x[j] (a bin centre,
/// or one cell of nearby sample values: the all-but-unbinned fit); returns b_k (b_ref = 0) and
/// ln Z_k − ln Z_ref; connected[k] says whether run k is linked to the reference, given or
/// (empty) found through bins that two runs share
struct JointFit {
  std::vector<double> b;        ///< b_k − b_ref, 1/(units of x)
  std::vector<double> dlnz;     ///< ln Z_k − ln Z_ref
  std::vector<bool> connected;  ///< linked to the reference by shared bins
  bool converged = false;
  int iterations = 0;
  std::int64_t terms = 0;  ///< Σ over objective evaluations of occupied cells × runs (its work)
};
JointFit joint_histogram_fit(const std::vector<std::vector<double>>& counts,
                             const std::vector<double>& x, int ref,
                             const std::vector<double>& b_start, int max_iterations,
                             double tolerance, const std::vector<bool>& connected = {},
                             const std::vector<double>& dlnz_start = {});

}  // namespace gs

// descriptive statistics of a series of measurements (docs/physics.md §2.6): mean, standard
// deviation, confidence intervals (Student t for the mean, chi-square for σ), the integrated
// autocorrelation time of correlated series (Sokal's automatic window) and a binned
// chi-square test of normality. Pure functions on std::vector<double>; the distribution
// functions and quantiles they need (incomplete gamma and beta) live here as well.
#pragma once
#include <vector>

namespace gs {

// ---- special functions and distributions ------------------------------------------------

/// regularized lower incomplete gamma P(a, x) = γ(a, x)/Γ(a), a > 0, x ≥ 0
double gamma_p(double a, double x);
/// regularized upper incomplete gamma Q(a, x) = 1 − P(a, x)
double gamma_q(double a, double x);
/// regularized incomplete beta I_x(a, b), a, b > 0, 0 ≤ x ≤ 1
double beta_inc(double a, double b, double x);

/// standard normal cumulative distribution Φ(x)
double normal_cdf(double x);
/// standard normal quantile Φ⁻¹(p), 0 < p < 1
double normal_quantile(double p);
/// chi-square cumulative distribution with k (real, > 0) degrees of freedom
double chi2_cdf(double x, double k);
/// chi-square quantile: the x with chi2_cdf(x, k) = p, 0 < p < 1
double chi2_quantile(double p, double k);
/// Student t cumulative distribution with ν (real, > 0) degrees of freedom
double student_t_cdf(double t, double nu);
/// Student t quantile: the t with student_t_cdf(t, ν) = p, 0 < p < 1
double student_t_quantile(double p, double nu);

// ---- moments and intervals --------------------------------------------------------------

/// a closed interval [lo, hi] in the units of the data
struct Interval {
  double lo = 0.0;  ///< lower bound, data units
  double hi = 0.0;  ///< upper bound, data units
  bool contains(double v) const { return lo <= v && v <= hi; }
};

/// arithmetic mean (throws std::invalid_argument on an empty series)
double mean(const std::vector<double>& x);
/// sample variance with the n − 1 denominator (needs n ≥ 2)
double variance(const std::vector<double>& x);
/// sample standard deviation with the n − 1 denominator (needs n ≥ 2)
double stddev(const std::vector<double>& x);

/// confidence interval of the mean from the Student t distribution. tau_int = 0.5 treats the
/// samples as independent; a larger integrated autocorrelation time τ_int inflates the
/// interval through the effective sample size n_eff = n/(2 τ_int) (dof n_eff − 1).
Interval mean_ci(const std::vector<double>& x, double level = 0.95, double tau_int = 0.5);
/// chi-square confidence interval of the standard deviation σ:
/// σ² ∈ [(ν s²)/χ²_{1−α/2}(ν), (ν s²)/χ²_{α/2}(ν)] with ν = n_eff − 1, n_eff = n/(2 τ_int)
Interval stddev_ci(const std::vector<double>& x, double level = 0.95, double tau_int = 0.5);

// ---- autocorrelation --------------------------------------------------------------------

/// integrated autocorrelation time with Sokal's automatic window
struct AutocorrTime {
  double tau_int = 0.5;     ///< τ_int = 1/2 + Σ_{t=1..M} ρ(t), in samples (taps)
  double tau_err = 0.0;     ///< statistical error of τ_int, σ² ≈ 2(2M+1)/n · τ² (Sokal)
  int window = 0;           ///< the window M: the smallest M with M ≥ c τ_int(M)
  bool converged = false;   ///< false when no such M < n/2 exists (series too short)
  std::vector<double> rho;  ///< normalized autocorrelation ρ(t), t = 0..M
};

/// integrated autocorrelation time of a series (Sokal 1997, window constant c, default 5).
/// The autocovariance uses the biased 1/n estimator around the sample mean.
AutocorrTime autocorr_time(const std::vector<double>& x, double c = 5.0);

/// where the steady part of a series begins, by the marginal standard error rule (MSER-b;
/// White 1997, White, Cobb & Spratt 2000): over the means of consecutive batches of `batch`
/// samples, the truncation d that minimises s²_d/(n − d), the squared standard error of the mean
/// of what is left, searched over d ≤ n/2
struct Truncation {
  int drop = 0;        ///< samples to drop from the start (a multiple of the batch)
  bool steady = true;  ///< false when the minimum sits at n/2: no steady part was found
};
Truncation mser_truncation(const std::vector<double>& x, int batch = 5);

// ---- normality --------------------------------------------------------------------------

/// result of a binned chi-square test against a fitted normal distribution
struct NormalityTest {
  double statistic = 0.0;  ///< X² = Σ (O − E)²/E, dimensionless
  int bins = 0;            ///< number of (equiprobable) bins k
  int dof = 0;             ///< degrees of freedom k − 1 − 2 (mean and σ were estimated)
  double p_value = 1.0;    ///< probability of a larger X² under normality
  bool normal = true;      ///< true when the hypothesis "normal" is not rejected at alpha
};

/// chi-square goodness-of-fit test of normality at significance alpha. The bins are
/// equiprobable under N(mean, s); bins = 0 picks k = round(2 n^{2/5}) (at least 4, and at
/// most n/5 so that every expected count is ≥ 5). Needs n ≥ 20.
NormalityTest normality_chi2(const std::vector<double>& x, double alpha = 0.05, int bins = 0);

}  // namespace gs

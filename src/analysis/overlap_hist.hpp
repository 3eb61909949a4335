// overlapping histograms (paper section II.D and V; P.19, P.20, P.39): the log ratio
// Q = ln(P₁/P₀) of the densities of two samples of a volume-like variable is a straight line
// when both are Boltzmann-like, Q = −(β₁ − β₀)·V − ln(Z₁/Z₀). A weighted line fit gives the
// relative inverse compactivity and partition function; a quadratic fit measures how far Q is
// from a line (Gaussian samples give a parabola, appendix A, A1).
#pragma once
#include <string>
#include <vector>

#include "analysis/kde.hpp"

namespace gs {

/// how the two densities are estimated on the common binning
enum class DensityMethod {
  Histogram,  ///< counts per common bin, binomial (Poisson-ratio) fit: σ_Q² = 1/n₁ + 1/n₀
  Kde         ///< kernel estimate at the bin centres; asymptotic variance P R(K)/(n h)
};

/// choices of the overlapping-histogram method
struct OverlapOptions {
  DensityMethod method = DensityMethod::Histogram;  ///< density estimate (default histogram)
  int bins = 0;                ///< common bins over the pair's range; 0: Scott's rule (below)
  double min_fraction = 0.05;  ///< keep bins where both densities exceed this share of their max
  Kernel kernel = Kernel::Normal;  ///< kernel of the estimates that define the region (and of
                                   ///< the KDE method's densities)
  double bandwidth = 0.0;          ///< their h in units of the variable; 0: Silverman per sample
};

/// one point of the Q line
struct QPoint {
  double x = 0.0;      ///< the volume-like variable at the bin centre (V, or 1/φ), its units
  double q = 0.0;      ///< Q = ln(P₁/P₀), dimensionless
  double q_err = 0.0;  ///< standard error of Q, dimensionless
};

/// the line (and parabola) through Q against the variable
struct QFit {
  bool valid = false;                ///< false when fewer than 3 usable points overlap
  std::string note;                  ///< why the fit is not valid, or caveats
  std::vector<QPoint> points;        ///< the points used (both densities above threshold)
  double slope = 0.0;                ///< dQ/dx, 1/(units of x)
  double slope_err = 0.0;            ///< standard error of the slope, 1/(units of x)
  double intercept = 0.0;            ///< Q at x = 0, dimensionless
  double intercept_err = 0.0;        ///< standard error of the intercept
  double cov_slope_intercept = 0.0;  ///< covariance of slope and intercept, 1/(units of x)
  double chi2 = 0.0;       ///< Pearson χ² of the line (histogram: binomial), dimensionless
  int dof = 0;             ///< points − 2
  double r2 = 0.0;         ///< weighted coefficient of determination of the line
  double quad = 0.0;       ///< c of the weighted fit Q = a + b x + c x², 1/(units of x)²
  double quad_err = 0.0;   ///< standard error of c (NaN with fewer than 4 points)
  double bin_width = 0.0;  ///< width of the common bins, units of x
};

/// the Q line of `sample` (P₁) against `ref` (P₀) on a common binning of the pair's range.
/// Scott's rule picks the bin width w = 3.49·min(σ₀ n₀^{−1/3}, σ₁ n₁^{−1/3}) when bins = 0.
/// The fitted region is where the kernel estimates of both densities exceed min_fraction of
/// their maxima (smooth estimates, so the region does not follow the noise of the counts).
/// Histogram method: given the total count t_j of a bin, the sample's count is binomial with
/// logit p_j = ln(n₁/n₀) + Q(x_j); this logistic fit is the exact Poisson likelihood of the
/// histogram ratio, so low counts need no cut and ln(counts) no bias correction; its
/// parameter errors are the Poisson errors propagated at the expected counts.
/// KDE method: weighted least squares on ln(P̂₁/P̂₀); the estimates at neighbouring bin
/// centres are correlated over ≈ 2h, so the parameter errors are inflated by the number of
/// points per correlation length (and χ² is not a goodness-of-fit measure there).
QFit q_fit(const std::vector<double>& ref, const std::vector<double>& sample,
           const OverlapOptions& opts = {});

/// inverse compactivity and partition function of a sample relative to a reference
struct BetaEstimate {
  bool valid = false;      ///< as QFit::valid
  double dbeta = 0.0;      ///< β − β_ref, 1/m² (1/(units of V) in general)
  double dbeta_err = 0.0;  ///< standard error of dbeta, same units
  double dlnz = 0.0;       ///< ln Z − ln Z_ref, dimensionless (P.40)
  double dlnz_err = 0.0;   ///< standard error of dlnz
  double cov = 0.0;        ///< covariance of dbeta and dlnz, same units as dbeta
  QFit fit;                ///< the Q line, against 1/φ (from φ) or V (from volumes)
};

/// from volume fractions (P.39): Q against 1/φ has slope −(β − β_ref)·V_g and intercept
/// −ln(Z/Z_ref); v_g is the (constant) grain volume in the test region, m²
BetaEstimate beta_from_phi(const std::vector<double>& phi_ref, const std::vector<double>& phi,
                           double v_g, const OverlapOptions& opts = {});
/// the same for several samples against one reference
std::vector<BetaEstimate> betas_from_phi(const std::vector<double>& phi_ref,
                                         const std::vector<std::vector<double>>& samples,
                                         double v_g, const OverlapOptions& opts = {});
/// from volumes directly (P.20): Q against V has slope −(β − β_ref), intercept −ln(Z/Z_ref)
BetaEstimate beta_from_volume(const std::vector<double>& v_ref, const std::vector<double>& v,
                              const OverlapOptions& opts = {});

/// the estimate with its variances multiplied by `factor` (≥ 1) for serially correlated
/// samples: the histogram counts of a series with integrated autocorrelation time τ_int vary
/// ≈ 2τ_int times more than Poisson counts, so a pair (τ₀, τ₁) takes factor = τ₀ + τ₁
/// (= 1 for independent samples). Errors of Q and parameters scale by √factor, χ² by 1/factor.
BetaEstimate with_variance_factor(BetaEstimate b, double factor);

/// a weighted polynomial least-squares fit y ≈ Σ_j c_j x^j, errors σ_i (all > 0)
struct PolyFit {
  std::vector<double> coef;              ///< c_0 … c_degree, in the units of y/x^j
  std::vector<std::vector<double>> cov;  ///< covariance of the coefficients
  double chi2 = 0.0;                     ///< Σ ((y − fit)/σ)²
  double r2 = 0.0;                       ///< weighted coefficient of determination
};
/// the fit is done in centred, scaled x for conditioning and transformed back exactly
PolyFit weighted_polyfit(const std::vector<double>& x, const std::vector<double>& y,
                         const std::vector<double>& sigma, int degree);
/// weighted R² = 1 − χ²/Σ w (y − ȳ_w)², w = 1/σ², given the fit's χ² (residual sum)
double weighted_r2(const std::vector<double>& y, const std::vector<double>& sigma, double chi2);

}  // namespace gs

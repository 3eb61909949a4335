// free paths of the 2D RFM (thesis §4.3): the distance l between leaving one contact and the
// next contact (T.4.18), histogrammed in logarithmic bins, and the fractal-background form
//   P_l(l) = A₀ l^(D_f−2) exp(−C l^(D_f−1))   (T.4.25)
// fitted with D_f, C and A₀ free (Levenberg–Marquardt on Poisson-weighted densities). Note
// that T.4.25 with β = D_f − 1 is a Weibull density: C l^β is exponentially distributed and
// A₀ = C β when the form holds for all l.
#pragma once
#include <filesystem>
#include <span>

#include "analysis/rfm_hist.hpp"
#include "core/records.hpp"

namespace gs::rfm {

/// an empty log-binned histogram of free paths on [l_min, l_max), m
Histogram free_path_histogram(double l_min, double l_max, int n_bins);

/// A₀ l^(D_f−2) exp(−C l^(D_f−1)) (T.4.25), 1/m
double free_path_density(double l, double a0, double c, double d_f);

/// the fit of T.4.25
struct FreePathFit {
  double d_f = 0.0, d_f_err = 0.0;  ///< fractal dimension, dimensionless
  double c = 0.0, c_err = 0.0;      ///< C, m^(1−D_f)
  double a0 = 0.0, a0_err = 0.0;    ///< A₀, m^(1−D_f)
  double chi2_r = 0.0;              ///< reduced χ², dimensionless
  int points = 0;                   ///< bins used
  double l_min = 0.0;               ///< centre of the first bin used, m
};

/// fits T.4.25 to the bins with l ≥ l_fit_min and at least min_count samples. The start
/// comes from a scan over D_f in which ln P − (D_f − 2) ln l is linear in l^(D_f−1).
/// Errors are inflated by √χ²_r when χ²_r > 1.
FreePathFit fit_free_paths(const Histogram& h, double l_fit_min = 0.0, double min_count = 10.0);

/// where the thesis' fit window begins: the centre of the first bin of the tail in which
/// every occupied bin has P_l < p_below (1/m; §4.3.3 fits "the lowest decades of data ...
/// where P < 1"); +∞ when the last occupied bin is not below it
double tail_start(const Histogram& h, double p_below);

/// columns l, count, P, P_err, P_fit (NaN without a fit); metadata D_f, C, A0 and errors
void write_freepath_csv(const RecordSink& sink, const std::filesystem::path& path,
                        const Histogram& h, const FreePathFit* fit = nullptr);

}  // namespace gs::rfm

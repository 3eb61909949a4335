// kernel density estimation (paper appendix B): P(x) = 1/(n h) Σ K((x − x_i)/h) (B1) with the
// normal, Epanechnikov and box kernels (B3, B5, B6) and Silverman's bandwidth (B7).
#pragma once
#include <string>
#include <vector>

namespace gs {

/// the kernels of appendix B (each integrates to one, B2)
enum class Kernel {
  Normal,  ///< (2π)^{-1/2} exp(−u²/2) (B3, normalisation corrected: docs/physics.md §8.9)
  Epanechnikov,  ///< (3/4)(1 − u²) on [−1, 1] (B5)
  Box            ///< 1 on [−1/2, 1/2] (B6): a shifted histogram of bin width h
};

/// the kernel's name as written in files ("normal", "epanechnikov", "box")
std::string kernel_name(Kernel k);
/// the kernel from its name; throws std::invalid_argument for an unknown name
Kernel kernel_from_name(const std::string& name);

/// K(u) of the chosen kernel, dimensionless
double kernel_value(Kernel k, double u);
/// R(K) = ∫ K(u)² du: sets the variance of the estimate, Var P̂(x) ≈ P(x) R(K)/(n h)
double kernel_roughness(Kernel k);
/// half-width of the kernel's support in units of h (infinite support: where K < 1e-16 K(0))
double kernel_reach(Kernel k);

/// Silverman's rule of thumb h = 1.06 σ n^{−1/5} (B7), σ the sample standard deviation
double silverman_bandwidth(const std::vector<double>& x);

/// the bandwidth of kernel k that smooths as much as a normal kernel of bandwidth h_normal:
/// canonical bandwidths (Marron & Nolan 1988), h_k = h_normal·δ_k/δ_normal with
/// δ = (R(K)/μ₂(K)²)^{1/5}; ×2.214 for Epanechnikov, ×3.480 for the box. (B1) takes h as the
/// kernel's own scale, so the same h smooths the compact kernels much less.
double equivalent_bandwidth(Kernel k, double h_normal);

/// n equally spaced points from a to b inclusive (n ≥ 2)
std::vector<double> linspace(double a, double b, int n);

/// the estimate (B1) at each grid point, in 1/(units of x); h in units of x
std::vector<double> kde(const std::vector<double>& x, const std::vector<double>& grid, double h,
                        Kernel k = Kernel::Normal);

/// the estimate at the centres lo + (j + ½)·width of nb bins that hold every sample, in
/// O(n + nb·h/δ) instead of kde()'s O(n·nb): for the normal kernel the samples are first shared
/// between the two nearest centres of a grid δ ≤ h/32 fine (linear binning; relative error
/// ≈ (δ/h)²/12 ≤ 1e-4); the other kernels, short-ranged, are summed exactly
std::vector<double> kde_on_bins(const std::vector<double>& x, double lo, double width, int nb,
                                double h, Kernel k = Kernel::Normal);

/// a density estimate on a grid
struct KdeCurve {
  std::vector<double> x;        ///< grid, units of the data
  std::vector<double> density;  ///< estimated density, 1/(units of the data)
  double bandwidth = 0.0;       ///< h, units of the data
};

/// estimate on `points` grid points spanning [min − pad·h, max + pad·h] with h from
/// Silverman's rule (or `h` when h > 0)
KdeCurve kde_auto(const std::vector<double>& x, int points = 256, Kernel k = Kernel::Normal,
                  double h = 0.0, double pad = 3.0);

}  // namespace gs

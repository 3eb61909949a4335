// the uniform multiplicative bisection process (thesis §3.4, T.3.26–T.3.38): [0, 1] is split
// n times, every segment at a uniform fraction a of its length (T.3.26–3.27), giving 2^n
// segments whose lengths are products of n uniforms (T.3.28). A segment picked uniformly
// among the 2^n has the density
//   P_n(x) = (−ln x)^(n−1)/(n−1)!  on 0 < x ≤ 1   (T.3.36),
// already normalised (∫P_n = Γ(n)/(n−1)! = 1; ⟨x⟩ = 2^(−n) so the 2^n segments fill [0, 1]),
// with moments ⟨x^m⟩ = (1+m)^(−n) (T.3.37), i.e. ⟨x^m⟩ = N^(−ln(1+m)/ln 2) for N = 2^n
// (T.3.38). A segment picked by a uniform point of [0, 1] (length-biased) instead has the
// density 2^n·x·P_n(x). The boundaries, read as 2^n point-particles on a ring of length 1,
// make a 1D configuration whose nearest-neighbour distribution G₁ (T.3.21) is P_n itself —
// the comparison of thesis Fig. 3.16.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "analysis/rfm_gaps.hpp"
#include "core/records.hpp"
#include "core/rng.hpp"

namespace gs::models {

/// settings of a bisection run
struct BisectionParams {
  int levels = 9;            ///< n: 2^n segments (the thesis uses 9)
  long realisations = 2000;  ///< independent intervals
  std::uint64_t seed = 1;    ///< random seed
  int bins = 60;             ///< logarithmic bins of x
  double x_min = 1e-9;       ///< lower edge of the bins (upper edge is 1)
  int m_max = 6;             ///< highest moment ⟨x^m⟩
  void validate() const;     ///< throws gs::InputError on bad values
};

/// segment lengths after `levels` bisections, in their order along [0, 1] (sum 1)
std::vector<double> bisect(int levels, RngStream& rng);

/// P_n(x) = (−ln x)^(n−1)/(n−1)! (T.3.36)
double bisection_density(double x, int n);
/// P(X ≤ x) = Q(n, −ln x) = x Σ_{k<n} (−ln x)^k/k! (regularised upper incomplete gamma)
double bisection_cdf(double x, int n);
/// ⟨x^m⟩ = (1+m)^(−n) (T.3.37)
double bisection_moment(int m, int n);
/// the length-biased density 2^n x P_n(x)
double bisection_density_length_biased(double x, int n);

/// one logarithmic bin of the segment-length distribution
struct BisectionBin {
  double lo = 0.0, hi = 0.0, x = 0.0;  ///< edges and geometric centre, fraction of the interval
  double p = 0.0;                      ///< measured density, per unit length
  double p_err = 0.0;                  ///< its error from the scatter between realisations
  double p_exact = 0.0;                ///< exact bin average of P_n
  double g1 = 0.0;                     ///< G₁ of the boundaries as particles (T.3.21)
  double g2 = 0.0;                     ///< G₂ of the same particles (T.3.24)
  double p_exact_prev = 0.0;  ///< exact bin average of P_(n−1), the T.3.25 partner of G₂
};

/// the measured and exact statistics of a run
struct BisectionResult {
  int levels = 0;
  std::vector<BisectionBin> bins;
  std::vector<double> moments;       ///< ⟨x^m⟩, m = 1…m_max
  std::vector<double> moment_err;    ///< errors from the scatter between realisations
  std::vector<double> moment_exact;  ///< (1+m)^(−n)
};

/// runs the process; realisation i uses the stream (seed, i)
BisectionResult run_bisection(const BisectionParams& p);

/// columns x, x_lo, x_hi, P, P_err, P_exact, G1, G2, P_exact_prev; metadata levels
void write_bisection_csv(const RecordSink& sink, const std::filesystem::path& path,
                         const BisectionResult& r);

}  // namespace gs::models

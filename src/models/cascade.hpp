// multiplicative cascades on a 2ⁿ×2ⁿ grid (thesis chapter 6, T.6.1–T.6.5). Level by level,
// every square splits into four and its mass m is shared by weights W_q, q = g + 2h for the
// child (2i+g, 2j+h), g, h ∈ {0, 1}:
//   UCP          W_q = a_q / Σa, four a_q uniform on (0, 1)                 (T.6.2–6.3)
//   UnonCP       W_q = a_q / 2  (the thesis' A = 1, scaled by ½ so that E[ΣW] = 1)
//   symmetrised  (a, 1−a, 1−a, a)/2 with a uniform on (0, ½), (g,h) = (0,0),(1,0),(0,1),(1,1)
//                (T.6.4; the pairs sum to 1, so ΣW = 1)
//   Meakin 1–4   the four p_i of Table 6.1, normalised to sum 1 (Meakin 3 prints 0.99 and
//                Meakin 4 1.01), assigned to the children in a random order each split
// The structure factor of the mass field S(k) = ⟨|Σ m_ij exp(i k·r_ij)|²⟩ (T.6.5, no 1/N) is
// taken by FFT on k = (2π/L)(n_x, n_y) and shell-averaged like the particle S(k). Its
// expectation is computed exactly too, by a recursion over levels on the weights' first and
// second moments. The correlation dimension D₂ = −log₂ E[Σ_q W_q²] is the exact reference
// for the D_f fit (UCP 1.6077, UnonCP and symmetrised log₂3 = 1.5850).
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/rfm_sk.hpp"
#include "core/records.hpp"
#include "core/rng.hpp"

namespace gs::models {

/// the weight rules of chapter 6
enum class CascadeKind { ucp, unoncp, symmetrised, meakin1, meakin2, meakin3, meakin4 };
/// "ucp", "unoncp", "symmetrised", "meakin1" … "meakin4"
std::string_view cascade_name(CascadeKind k);
/// the inverse of cascade_name; throws gs::InputError naming the unknown value
CascadeKind cascade_from_name(std::string_view name);

/// one split's four weights (child q = g + 2h), drawn by the rule of `kind`
std::array<double, 4> cascade_weights(CascadeKind kind, RngStream& rng);

/// the exact first and second moments of the four weights
struct WeightMoments {
  std::array<double, 4> mean{};                   ///< E[W_q]
  std::array<std::array<double, 4>, 4> second{};  ///< E[W_q W_p]
};
WeightMoments cascade_weight_moments(CascadeKind kind);
/// D₂ = −log₂ E[Σ_q W_q²]; for UCP by quadrature (E[a₁²/(Σa)²] over the Irwin–Hall density)
double correlation_dimension(CascadeKind kind);

/// why S(k) of this kind is not a power law, or "" when it can be: the symmetrised rule gives
/// both rows and both columns of every split the same mass, so the field's projections on x and
/// y are uniform and S(k) vanishes on the k_x and k_y axes
std::string cascade_no_power_law_reason(CascadeKind kind);

/// the masses after `levels` splits of a unit mass, row-major m[j·2ⁿ + i] (i along x)
std::vector<double> cascade_field(CascadeKind kind, int levels, RngStream& rng);

/// settings of a cascade S(k) run
struct CascadeParams {
  CascadeKind kind = CascadeKind::ucp;  ///< weight rule
  int levels = 8;                       ///< n: a 2ⁿ×2ⁿ grid (the thesis uses 8)
  long realisations = 100;              ///< independent fields averaged
  std::uint64_t seed = 1;               ///< realisation r uses the stream (seed, r)
  int n_max = 0;                        ///< |n| cutoff of the shells; 0 → 2^(n−1) (Nyquist)
  double box = 1.0;                     ///< L, m (only scales k)
  void validate() const;                ///< throws gs::InputError on bad values
};

/// the measured S(k) and the mass statistics of a run
struct CascadeResult {
  std::vector<rfm::SkShell> shells;  ///< configuration-averaged S(k), shells of equal n²
  double mass_mean = 0.0;            ///< ⟨Σm⟩ over realisations (1 unless UnonCP)
  double mass_err = 0.0;             ///< its standard error
};
/// S(k) of T.6.5 averaged over realisations (FFTW r2c when available)
CascadeResult cascade_structure_factor(const CascadeParams& p);
/// the exact E[S(k)] on the same shells
std::vector<rfm::SkShell> cascade_expected_sk(CascadeKind kind, int levels, int n_max,
                                              double box = 1.0);

/// columns k, n, S, S_err, S_exact; metadata D2 and the fit (D_f, D_f_err, A, k_lo, k_hi)
void write_cascade_csv(const RecordSink& sink, const std::filesystem::path& path,
                       const CascadeResult& r, const std::vector<rfm::SkShell>& exact,
                       CascadeKind kind, const rfm::DfFit* fit = nullptr);

}  // namespace gs::models

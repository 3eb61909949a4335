// synthetic tapping data with known answers: an ideal quadron gas (P.21) sampled exactly.
// The test region holds N z̄ = round(a V_g) independent cells whose volumes are distributed
// ∝ exp(−β v) on [V₀ − Δ, V₀ + Δ] (flat density of states), V₀ = 1/(a φ_rlp), Δ = Δφ⁻¹/a.
// φ = V_g/Σv then has exactly the canonical distribution whose mean is (P.26), whose
// ln Z is (P.21) and whose fluctuations follow (P.17) to first order in σ_V/V.
// Consecutive taps redraw each cell with probability p (keep it otherwise): the stationary
// distribution stays canonical and the autocorrelation is ρ(t) = (1 − p)^t, so
// τ_int = (2 − p)/(2p). Used by the tests and to demonstrate the charts.
#pragma once
#include <cstdint>
#include <vector>

#include "analysis/quadron.hpp"
#include "analysis/tap_analysis.hpp"

namespace gs {

/// the synthetic ideal quadron gas
struct QuadronGasSpec {
  double a = 556.5;          ///< N z̄/V_g, 1/m² (rounded so that N z̄ = round(a V_g))
  double v_g = 0.13;         ///< grain volume in the test region, m²
  QuadronParams limits;      ///< φ_rlp, φ_rcp
  double refresh = 1.0;      ///< probability that a cell is redrawn at a tap, 0 < p ≤ 1
  double start_fill = -1.0;  ///< initial cell volume as v = V₀ + start_fill·Δ; < −1: equilibrium
};

/// the number of cells N z̄ = max(1, round(a V_g))
int quadron_gas_cells(const QuadronGasSpec& g);
/// the exact a = N z̄/V_g the sampler realizes, 1/m²
double quadron_gas_a(const QuadronGasSpec& g);

/// a series of `taps` values of φ at inverse compactivity β (1/m²), deterministic in
/// (seed, stream). start_fill in [−1, 1] starts every cell at V₀ + start_fill·Δ (a transient).
std::vector<double> quadron_gas_phi(double beta, int taps, const QuadronGasSpec& g,
                                    std::uint64_t seed, std::uint64_t stream);

/// the same as a taps.csv series: tap = 1…taps, φ, and the halves φ_left, φ_right (the first
/// and second half of the cells, each holding grain volume V_g/2), so σ_half/σ ≈ √2
TapSeries quadron_gas_taps(double beta, int taps, const QuadronGasSpec& g, std::uint64_t seed,
                           std::uint64_t stream);

/// the volume of one cell drawn ∝ exp(−β v) on [lo, lo + w] from a uniform u in (0, 1)
double truncated_exponential(double beta, double lo, double w, double u);

}  // namespace gs

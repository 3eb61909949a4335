// exact sampling of the ideal quadron gas (P.21) for tests and chart demonstrations
#include "analysis/tap_synthetic.hpp"

#include <cmath>
#include <stdexcept>

#include "core/rng.hpp"

namespace gs {

int quadron_gas_cells(const QuadronGasSpec& g) {
  return std::max(1, static_cast<int>(std::lround(g.a * g.v_g)));
}

double quadron_gas_a(const QuadronGasSpec& g) { return quadron_gas_cells(g) / g.v_g; }

double truncated_exponential(double beta, double lo, double w, double u) {
  // inverse cdf of ∝ e^{−βv} on [lo, lo + w]: v = lo − ln(1 + u (e^{−βw} − 1))/β, uniform at β → 0
  const double bw = beta * w;
  if (std::abs(bw) < 1e-12) return lo + u * w;
  return lo - std::log1p(u * std::expm1(-bw)) / beta;
}

std::vector<double> quadron_gas_phi(double beta, int taps, const QuadronGasSpec& g,
                                    std::uint64_t seed, std::uint64_t stream) {
  if (!(g.refresh > 0.0 && g.refresh <= 1.0))
    throw std::invalid_argument("quadron_gas_phi: refresh must lie in (0, 1]");
  const int n = quadron_gas_cells(g);
  const double a = quadron_gas_a(g);
  // per-cell limits from (P.24), (P.25): V₀ = 1/(a φ_rlp), Δ = Δφ⁻¹/a
  const double v0 = 1.0 / (a * g.limits.phi_rlp);
  const double delta = g.limits.delta_inv() / a;
  RngStream rng(seed, stream);
  std::vector<double> cells(n);
  for (auto& c : cells)
    c = g.start_fill >= -1.0 ? v0 + g.start_fill * delta
                             : truncated_exponential(beta, v0 - delta, 2.0 * delta, rng.uniform());
  // each tap: redraw every cell with probability p, then measure φ = V_g/Σv
  std::vector<double> phi(taps);
  for (int t = 0; t < taps; ++t) {
    double vol = 0.0;
    for (auto& c : cells) {
      if (g.refresh >= 1.0 || rng.uniform() < g.refresh)
        c = truncated_exponential(beta, v0 - delta, 2.0 * delta, rng.uniform());
      vol += c;
    }
    phi[t] = g.v_g / vol;
  }
  return phi;
}

}  // namespace gs

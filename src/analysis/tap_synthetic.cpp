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

TapSeries quadron_gas_taps(double beta, int taps, const QuadronGasSpec& g, std::uint64_t seed,
                           std::uint64_t stream) {
  if (!(g.refresh > 0.0 && g.refresh <= 1.0))
    throw std::invalid_argument("quadron_gas_taps: refresh must lie in (0, 1]");
  const int n = quadron_gas_cells(g);
  const int half = n / 2;
  const double a = quadron_gas_a(g);
  // per-cell limits from (P.24), (P.25): V₀ = 1/(a φ_rlp), Δ = Δφ⁻¹/a
  const double v0 = 1.0 / (a * g.limits.phi_rlp);
  const double delta = g.limits.delta_inv() / a;
  RngStream rng(seed, stream);
  std::vector<double> cells(n);
  for (auto& c : cells)
    c = g.start_fill >= -1.0 ? v0 + g.start_fill * delta
                             : truncated_exponential(beta, v0 - delta, 2.0 * delta, rng.uniform());
  // each tap: redraw every cell with probability p, then measure φ = V_g/Σv (and per half,
  // each half's grain volume in proportion to its cells)
  TapSeries s;
  s.source = "synthetic quadron gas";
  for (int t = 0; t < taps; ++t) {
    double vl = 0.0, vr = 0.0;
    for (int i = 0; i < n; ++i) {
      auto& c = cells[i];
      if (g.refresh >= 1.0 || rng.uniform() < g.refresh)
        c = truncated_exponential(beta, v0 - delta, 2.0 * delta, rng.uniform());
      (i < half ? vl : vr) += c;
    }
    s.tap.push_back(t + 1);
    s.phi.push_back(g.v_g / (vl + vr));
    if (half > 0) {
      s.phi_left.push_back(g.v_g * half / n / vl);
      s.phi_right.push_back(g.v_g * (n - half) / n / vr);
    }
  }
  return s;
}

std::vector<double> quadron_gas_phi(double beta, int taps, const QuadronGasSpec& g,
                                    std::uint64_t seed, std::uint64_t stream) {
  return quadron_gas_taps(beta, taps, g, seed, stream).phi;
}

}  // namespace gs

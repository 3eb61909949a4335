// the analytic steady state of thesis appendix B: particles released at rest at uniform
// positions in 0 < x < L at rate R per unit length, accelerated by white noise (velocity
// diffusion D_v = D/M²), absorbed at x = 0 and x = L. In reduced units ξ = x/L,
// u = v/(D_v L)^(1/3) the density for u > 0 is (B.32, up to its constant prefactor)
//   p(ξ, u) = −K ∫₀^ξ dy e^(−u³/(9(ξ−y))) (ξ−y)^(−2/3) [y(1−y)]^(−1/6) F(y)
//             + ∫₀^ξ dy y^(−2/3) e^(−u³/(9y)),
//   K = Γ(1/6)/(2√3 Γ(1/3) Γ(5/6)),  F(y) = ₂F₁(−⅓, 1; ⅚; 1−y) − ₂F₁(−⅓, 1; ⅚; y),
// and p(ξ, −u) = p(1−ξ, u) (property II). The printed prefactor R/Γ(⅔) does not give the
// arrival rate RL/2 at each end (it is off by 2·3^(1/3)), so everything here is normalised
// by ratios in which the prefactor cancels:
//  * the arrival-velocity density at x = L (thesis Fig. B.1): f(u) = u p(1, u)/∫u p(1, u) du,
//    with ∫u p(1, u) du = Γ(⅔) 3^(1/3) (F is odd about ½);
//  * the mean exit time ⟨τ⟩ = (particles present)/(injection rate) = ∫∫p /(2∫u p(1,u)du)
//    = c (L²/D_v)^(1/3) with c = Γ(4/3) 3^(1/3)/Γ(⅔) · [9/10 − (3K/2) ∫₀¹ [y(1−y)]^(−1/6)
//    (1−y)^(2/3) F(y) dy] ≈ 1.0191.
#pragma once
#include <functional>

namespace gs::models {

/// Gauss's ₂F₁(a, b; c; z) for 0 ≤ z ≤ 1: the series for z ≤ ½, the 1 − z connection formula
/// above (needs c − a − b not an integer; throws gs::InputError otherwise)
double hyp2f1(double a, double b, double c, double z);

/// ∫_a^b f by tanh–sinh quadrature, exact to ~1e-12 for analytic f with integrable endpoint
/// singularities; f receives (y, y − a, b − y) with the distances free of cancellation
double tanh_sinh(const std::function<double(double, double, double)>& f, double a, double b);

/// F(y) of B.31–B.32 (odd about y = ½)
double appendix_b_f(double y);
/// p(ξ, u) of B.32 without its prefactor, 0 < ξ ≤ 1, u > 0
double appendix_b_density(double xi, double u);
/// the density of arrival velocities at x = L in u = v/(D_v L)^(1/3), u > 0 (Fig. B.1)
double appendix_b_arrival_density(double u);
/// c in ⟨τ⟩ = c (L² M²/D)^(1/3) for release at rest at a uniform position
double appendix_b_mean_exit_time_coefficient();

}  // namespace gs::models

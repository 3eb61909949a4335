// single-particle walks (thesis §5.2–5.3 and appendix B). A particle starts at rest and is
// kicked by the random force only: each step Δt it moves r ← r + v Δt and then gets the kick
// v ← v + η Δt/M with every component of η from N(0, 2D/Δt) (T.5.11, T.2.22–2.23), so each
// velocity component diffuses with D_v = D/M²: ⟨v_x²⟩ = 2 D t/M². It is absorbed the first time
// it is outside the region:
//  * disc_walk: the disc |r| ≤ l around the start (the Single Particle Model circle of fixed
//    free path l); velocities sampled every step (uniformly in time) give Q(v, l), which
//    collapses in v/l^(1/3) — the only velocity scale is (D l/M²)^(1/3);
//  * disc_walk_spm: the same with l drawn for every walk from a tabulated P_l (§5.2.3) — the
//    SPM integral identity P(v) = ∫ Q(v, l) P_l(l) dl (T.5.10);
//  * interval_walk: the 1D interval 0 < x < L of appendix B, started at rest at its centre or
//    at a uniform position; Q(v, L) (B.33) and the velocities of arrival at x = L (Fig. B.1).
// Two identities hold exactly for this discrete walk (optional stopping of martingales), so
// every result carries their residuals as checks of the kicks and of the time sampling:
//   E[|v_τ|² − 2·dim·D_v·τ] = 0,     E[(r_τ − r_0)·v_τ − Σ_{n<τ} |v_n|² Δt] = 0.
#pragma once
#include <cstdint>
#include <filesystem>
#include <vector>

#include "analysis/rfm_hist.hpp"
#include "core/records.hpp"

namespace gs::models {

/// settings of the walks
struct WalkParams {
  double noise = 1e-8;     ///< D, noise strength, N²·s (thesis value)
  double mass = 3.53e-5;   ///< M, particle mass, kg (thesis value)
  double dt = 0.0;         ///< time step, s; 0 → (l²M²/D)^(1/3)/1000 of the (smallest) region
  long walks = 10000;      ///< absorbed walks to simulate
  std::uint64_t seed = 1;  ///< walk i uses the random stream (seed, i)
  double v_max = 0.0;      ///< velocity histogram half-range, m/s; 0 → 8 (D l/M²)^(1/3)
  int bins = 400;          ///< velocity histogram bins
  long max_steps = 100'000'000;  ///< safety cap on the steps of one walk
  void validate() const;         ///< throws gs::InputError on bad values
};

/// (D l/M²)^(1/3): the velocity scale of a walk in a region of size l, m/s
double walk_velocity_scale(const WalkParams& p, double l);
/// (l² M²/D)^(1/3): the time scale of a walk in a region of size l, s
double walk_time_scale(const WalkParams& p, double l);

/// statistics of many absorbed walks
struct WalkResult {
  int dim = 2;                  ///< 1 (interval) or 2 (disc)
  double dt = 0.0;              ///< time step used, s
  rfm::Histogram q;             ///< velocity components sampled every step: Q(v, l)
  rfm::Histogram arrival;       ///< velocity that crossed the boundary (1D: at x = L only)
  long walks = 0;               ///< walks simulated
  long samples = 0;             ///< velocity samples (steps × dim)
  double mean_exit_time = 0.0;  ///< ⟨τ⟩, s
  double exit_time_err = 0.0;   ///< its standard error, s
  double mean_v2 = 0.0;         ///< ⟨v_x²⟩ over the time samples (components pooled), m²/s²
  double mean_region = 0.0;     ///< mean l (disc radius or interval length), m
  double heating_residual = 0.0, heating_residual_err = 0.0;  ///< ⟨|v_τ|² − 2 dim D_v τ⟩, m²/s²
  double virial_residual = 0.0, virial_residual_err = 0.0;  ///< ⟨Δr·v_τ − Σ|v|²Δt⟩, m²/s
  long capped = 0;  ///< walks stopped by max_steps (should be 0)
};

/// Q(v, l) of a particle started at rest at the centre of a disc of radius l (§5.3.1)
WalkResult disc_walk(const WalkParams& p, double radius);

/// a tabulated free-path density P_l, linear between its points
struct PathTable {
  std::vector<double> l;  ///< free paths, increasing, m
  std::vector<double> p;  ///< density at each l, 1/m (any normalisation)
  void validate() const;  ///< throws gs::InputError on bad tables
};
/// the Single Particle Model (§5.2.3): l of every walk drawn from the table (exact inverse
/// distribution function of the piecewise-linear density; the thesis uses acceptance–rejection,
/// which samples the same distribution)
WalkResult disc_walk_spm(const WalkParams& p, const PathTable& table);

/// where the 1D particle starts (appendix B uses uniform, the SPM picture the centre)
enum class IntervalStart { centre, uniform };
/// the 1D interval 0 < x < L with absorbing ends (appendix B)
WalkResult interval_walk(const WalkParams& p, double length, IntervalStart start);

/// mean squares of free particles (no boundary) against time
struct HeatingCurve {
  std::vector<double> t;       ///< times, s
  std::vector<double> v2;      ///< ⟨v_x²⟩ (components pooled), m²/s²
  std::vector<double> v2_err;  ///< its standard error, m²/s²
  std::vector<double> x2;      ///< ⟨x²⟩ (components pooled), m²
  std::vector<double> x2_err;  ///< its standard error, m²
};
/// `particles` free particles of dimension `dim` for `steps` steps of p.dt (must be > 0),
/// recorded every `every` steps. Exact: ⟨v_x²⟩ = 2 D_v t and, for the first-order update
/// T.5.11, ⟨x²⟩ = 2 D_v Δt³ (n−1) n (2n−1)/6 after n steps (→ (2/3) D_v t³).
HeatingCurve free_heating(const WalkParams& p, int dim, long particles, long steps, long every);

/// the coefficient c of the Gaussian tail Q ≈ A exp(−c (M²/(2Dl))^(2/3) v²) (T.5.12; the thesis
/// finds c ≈ 0.98), fitted on the bins whose Q lies between q_lo and q_hi times the peak
double gaussian_tail_coefficient(const WalkResult& r, const WalkParams& p, double radius,
                                 double q_hi = 1e-2, double q_lo = 1e-4);

/// columns v, u = v/(D l/M²)^(1/3), count, Q, Q_err, Q_scaled = Q·(D l/M²)^(1/3), arrival;
/// metadata dim, dt, radius, mean_exit_time, mean_v2 and the identity residuals
void write_walk_csv(const RecordSink& sink, const std::filesystem::path& path, const WalkResult& r,
                    const WalkParams& p, double radius);
/// the arrivals at x = L of an interval_walk against appendix B: columns u = v/(D_v L)^(1/3),
/// count, f, f_err (normalised over u > 0), f_theory (B.32); metadata mean_exit_time and
/// mean_exit_time_theory (uniform release)
void write_interval_csv(const RecordSink& sink, const std::filesystem::path& path,
                        const WalkResult& r, const WalkParams& p, double length);
/// columns t, v2, v2_err, v2_exact, x2, x2_err, x2_exact
void write_heating_csv(const RecordSink& sink, const std::filesystem::path& path,
                       const HeatingCurve& h, const WalkParams& p);

}  // namespace gs::models

// `gransim analyze` for Random Force Model runs (docs/physics.md §5.3, docs/rfm.md): the fits of
// the thesis on what the RFM observer wrote (measure/rfm_observer.hpp), per run and across system
// sizes, as CSV/JSON plus charts drawn by gransim.charts.rfm.
//   per run (OUT/<run name>/): temperature.csv, velocity.csv with the tail scan (appendix A:
//   counts 50…5000, accept α while χ²_r < 1.2) and the crossover fit (T.5.32), tail_scan.csv,
//   lnln_A0.csv / lnln_P0.csv (§5.3.3), velocity_post.csv (post-collision), moments.csv;
//   2D: sk.csv with the D_f fit below k′ (k_D / L_Eff rule, T.4.5–4.9), gr.csv; freepath.csv
//   with the fit of T.4.25 over l ≥ d/10; 1D: gh.csv, gap_moments.csv and gh_bisection.csv
//   (G₁ against the bisection density (−ln R)^(n−1)/(n−1)!, n = round(log₂N), and against
//   the gaps of N uniform points).
//   across runs (OUT/): exponents.csv (ξ_m from ⟨|v|^m⟩ ∝ N^(−ξ_m), T.3.13; ζ_m from
//   ⟨R^m⟩ ∝ N^(−ζ_m), T.3.20, for runs of one dimension and restitution at ≥ 2 sizes),
//   moments_vs_N.csv, and rfm_summary.json with every fit.
#pragma once
#include <string>
#include <vector>

namespace gs {

/// a run directory written with the RFM observer (DIR/rfm.json), or a folder holding such runs
bool is_rfm_run(const std::string& dir);

/// analyse the RFM runs found in `dirs` (runs or folders of runs) into `out`; charts with
/// gransim.charts.rfm unless `charts` is false (a missing python only warns); prints a
/// summary table unless quiet. Throws gs::InputError when no RFM run is found.
void analyze_rfm_runs(const std::vector<std::string>& dirs, const std::string& out,
                      bool charts = true, bool quiet = false);

/// draw the charts of one folder of RFM CSV files with gransim.charts.rfm; returns "" on
/// success, else what went wrong (no python, no matplotlib, script not found)
std::string draw_rfm_charts(const std::string& dir);

}  // namespace gs

"""The thesis' auxiliary-model claims: eq. 5.29 of the Single Particle Model (α from D_f, §5.3.2)
on the program's own D_f, the model's P(v) against the fluid's (Fig. 5.10) from
DIR/models/spm_seed<K> (`gransim model walk --paths`), and the multiplicative cascades' D_f
(Table 6.2) from DIR/models/cascade (`gransim model cascade`)."""
import json
import math
import os

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from .rfm_data import Missing, _ax, _chart, _ci, _csv, _gate, _runs, seed_mean, seed_text  # noqa: E402
from .rfm_fluid import (all_of, c_alpha_phi, c_crossover, c_gr, c_moments_phi, need,  # noqa: E402
                        point_at, value_part)
from .verdicts import UNRESOLVED, Verdict, compare_value, t_of  # noqa: E402

SPM_ALPHA, SPM_TOL = 0.972, 0.03  # eq. 5.29: "≈ 0.972 ± 0.03"


def alpha_of(df):
    """eq. 5.29: α = 6β/(3β + 2) with β = D_f − 1"""
    return 6 * (df - 1) / (3 * df - 1)


def dalpha(df):
    """dα/dD_f = 12/(3D_f − 1)²"""
    return 12 / (3 * df - 1) ** 2


def spm_verdict(df, err, dof=None):
    """α of eq. 5.29 from a measured D_f against the thesis' 0.972 ± 0.03; the alternative: twice
    its stated ±, as for D_f itself"""
    a, e = alpha_of(df), dalpha(df) * err
    return a, e, compare_value(a, e, SPM_ALPHA, tolerance=SPM_TOL, alternative=2 * SPM_TOL,
                               precision="the thesis' ± 0.03", fmt="{:.3g}", dof=dof)


def c_spm_alpha(d, sw="structure"):
    r = point_at(d, sw, 0.530)
    fits = [q.get("structure") for q in r["runs"]]
    ok = [f for f in fits if f and f.get("D_f") is not None]
    if not ok:
        raise Missing(f"no S(k) fit in analysis/{sw}: eq. 5.29 needs D_f")
    s = seed_mean([f["D_f"] for f in ok], [f["D_f_err"] for f in ok])
    a, e, v = spm_verdict(s["value"], s["err"], s["dof"])
    extra = ""
    for name in ("freepath",):  # the free paths' β = D_f − 1 enters the derivation itself (T.5.13)
        try:
            fp = [q.get("free_paths") for p in _runs(d, name) for q in p["runs"]]
        except Missing:
            continue
        fp = [f for f in fp if f and f.get("D_f") is not None]
        if fp:
            t = seed_mean([f["D_f"] for f in fp], [f["D_f_err"] for f in fp])
            extra = (f"; with the free paths' D_f = {_ci(t['value'], t['err'], t['dof'])} (sweep {name}) "
                     f"it gives α = {_ci(alpha_of(t['value']), dalpha(t['value']) * t['err'], t['dof'])}")
    reason = (f"{v.reason}; α = 6(D_f − 1)/(3D_f − 1) from the S(k) D_f = {_ci(s['value'], s['err'], s['dof'])} "
              f"(the thesis puts its S(k) value 1.63 ± 0.03 in){extra}")

    def draw(ax):
        dd = np.linspace(min(1.3, s["value"] - 0.1), max(1.9, s["value"] + 0.1), 100)
        ax.plot(dd, alpha_of(dd), "k", lw=0.8, label="eq. 5.29: α = 6(D_f − 1)/(3D_f − 1)")
        ax.axhspan(SPM_ALPHA - SPM_TOL, SPM_ALPHA + SPM_TOL, color="C3", alpha=0.2,
                   label="thesis: α ≈ 0.972 ± 0.03")
        ax.axvspan(1.60, 1.66, color="C3", alpha=0.08, label="thesis: D_f = 1.63 ± 0.03")
        k = t_of(0.05, s["dof"]) if s["dof"] else 1.96
        ax.errorbar([s["value"]], [a], [k * e], [k * s["err"]], fmt="o", color="C0",
                    capsize=3, label="gransim S(k) D_f and its α, 95 %")
        _ax(ax, f"the Single Particle Model's tail exponent (§5.3.2), φ = {r['phi']:.3g}",
            "D_f", "α", fs=7)
    return dict(measured=f"α = {_ci(a, e, s['dof'])} (95 %) from D_f = {_ci(s['value'], s['err'], s['dof'])}" + seed_text(s),
                verdict=_gate(Verdict(v.verdict, reason, v.null, v.alternative, v.power, v.scale_,
                                      v.power_at), [r]),
                chart=_chart(d, "spm-alpha", draw), values=dict(alpha=a, alpha_err=e, D_f=s["value"]))


# ---- the Single Particle Model's P(v) against the fluid's (Fig. 5.10) -----------------------------

def folded(v, count, edges):
    """the density of |v| on `edges` from a histogram of a velocity component, and its counts"""
    c, _ = np.histogram(np.abs(v), edges, weights=count)
    return c / (c.sum() * np.diff(edges)), c


def tail_slope(v_rfm, n_rfm, v_spm, n_spm, edges):
    """ln(P_RFM/P_SPM) = a + b|v| fitted on the tail (§5.2.3: the model describes the fast
    particles): the bins where the fluid's |v| density has fallen below a tenth of its first bin
    and both hold ≥ 10 counts, Poisson weights; (b, σ_b, a, the bins' mask)"""
    pr, cr = folded(v_rfm, n_rfm, edges)
    ps, cs = folded(v_spm, n_spm, edges)
    m = (pr < pr[0] / 10) & (cr >= 10) & (cs >= 10)
    if m.sum() < 3:
        raise Missing("fewer than three tail bins where the fluid and the model both hold ≥ 10 counts")
    x = 0.5 * (edges[:-1] + edges[1:])[m]
    y = np.log(pr[m] / ps[m])
    s = np.sqrt(1 / cr[m] + 1 / cs[m])
    w = 1 / s ** 2
    xm = (w * x).sum() / w.sum()
    b = float((w * (x - xm) * y).sum() / (w * (x - xm) ** 2).sum())
    a = float((w * (y - b * x)).sum() / w.sum())
    return b, float(((w * (x - xm) ** 2).sum()) ** -0.5), a, m


def spm_pv_verdict(b, err, dof=None):
    """the model's tail has the fluid's shape (slope 0 of the log ratio); the thesis sizes no
    agreement ("remarkably good over many decades"), so the test can disagree, never agree"""
    v = compare_value(b, err, 0.0, fmt="{:.3g}", dof=dof)
    return Verdict(v.verdict, "slope of ln(P_RFM/P_SPM) against |v| on the tail: " + v.reason,
                   "the tails differ by a constant factor (Fig. 5.10's vertical scaling)",
                   "none sized by the thesis", v.power, v.scale_, v.power_at)


def c_spm_pv(d, sw="freepath"):
    r = point_at(d, sw, 0.530)
    edges = np.linspace(0, 3.0, 121)
    fits = []
    for q in r["runs"]:
        k = q.get("seed") or "1"
        walk = os.path.join(d, "models", f"spm_seed{k}", "walk_spm.csv")
        if not os.path.exists(walk):
            continue
        a = need(d, os.path.join(q["adir"], "velocity.csv"))[0]
        b = need(d, walk)[0]
        fits.append((q, a, b) + tail_slope(a["v"], a["count"], b["v"], b["count"], edges))
    if not fits:
        raise Missing(f"models/spm_seed<K>/walk_spm.csv is missing for every run of sweep {sw}: "
                      "`gransim reproduce` runs the model after the sweep's analysis (not with "
                      "--report-only)")
    s = seed_mean([f[3] for f in fits], [f[4] for f in fits])
    v = spm_pv_verdict(s["value"], s["err"], s["dof"])

    def draw(ax):
        q, a, b, _, _, amp, m = fits[0]
        x = 0.5 * (edges[:-1] + edges[1:])
        pr, _ = folded(a["v"], a["count"], edges)
        ps, _ = folded(b["v"], b["count"], edges)
        ax.plot(x[pr > 0], pr[pr > 0], "k.", ms=4, label=f"gransim fluid, {q['name']}")
        ax.plot(x[ps > 0], math.exp(amp) * ps[ps > 0], "C0-", lw=1,
                label="Single Particle Model on the run's P_l, × e^a of the tail fit")
        ax.axvspan(x[m].min(), x[m].max(), color="C0", alpha=0.08, label="tail bins compared")
        _ax(ax, f"P(|v|) of the fluid and of the model, φ = {r['phi']:.3g}, L = "
            f"{r['info'].get('box', 0.6):g} m (thesis Fig. 5.10)", "|v| (m/s)", "P(|v|) (s/m)",
            False, True, 7)
    mid = 0.5 * (edges[:-1] + edges[1:])
    lo, hi = min(mid[f[6]].min() for f in fits), max(mid[f[6]].max() for f in fits)
    return dict(measured=f"tail slope of ln(P_RFM/P_SPM) = {_ci(s['value'], s['err'], s['dof'])} s/m (95 %) "
                f"over |v| = {lo:.2f}…{hi:.2f} m/s" + seed_text(s),
                verdict=_gate(v, [r]), chart=_chart(d, "spm-pv", draw),
                values=dict(slope=s["value"], slope_err=s["err"]))


# ---- the multiplicative cascades (Table 6.2) ------------------------------------------------------

# kind -> (D_f, its ±); the symmetrised cascade is "difficult to accurately fit" and has no entry
TABLE_6_2 = {"ucp": (1.602, 0.066), "unoncp": (1.595, 0.064), "meakin1": (1.287, 0.084),
             "meakin2": (1.596, 0.147), "meakin3": (1.828, 0.233), "meakin4": (1.689, 0.178)}
NAMES = {"ucp": "UCP", "unoncp": "UnonCP", "meakin1": "Meakin 1", "meakin2": "Meakin 2",
         "meakin3": "Meakin 3", "meakin4": "Meakin 4"}
LEVELS = 8  # §6.2.2: "breaking square regions into four until the eighth level is reached"
COMMAND = "gransim model cascade --kind all --levels 8 --realisations 500 --out DIR/models/cascade"


def cascade_verdict(fits):
    """each kind's D_f against Table 6.2, its ± the tolerance (the thesis' stated precision, from
    the systematic effects of its Fig. 6.2) and twice it the alternative, as for D_f of S(k)"""
    return all_of([value_part(NAMES[k], fits[k][0], fits[k][1], s, t, 2 * t, "Table 6.2's ±")
                   for k, (s, t) in TABLE_6_2.items() if k in fits],
                  "each a difference of twice Table 6.2's ±")


def c_cascade(d, sw=""):
    folder = os.path.join(d, "models", "cascade")
    p = os.path.join(folder, "model.json")
    if not os.path.exists(p):
        raise Missing("models/cascade/model.json is missing: `gransim reproduce` runs the "
                      "cascades after the sweeps (not with --report-only), or "
                      f"`{COMMAND}` writes it (≈ 1.5 CPU-minutes)")
    with open(p) as f:
        j = json.load(f)
    fits, levels = {}, set()
    for k in TABLE_6_2:
        if j.get(f"{k}_D_f") is not None and j.get(f"{k}_power_law", 1):
            fits[k] = (float(j[f"{k}_D_f"]), float(j[f"{k}_D_f_err"]), j.get(f"{k}_D2"))
        c = os.path.join(folder, f"cascade_{k}.csv")
        if os.path.exists(c):
            levels.add(int(round(math.log2(_csv(c)[0]["n"].max()))) + 1)  # |n| ≤ 2^(levels−1)
    if not fits:
        raise Missing("models/cascade/model.json has no D_f of the kinds of Table 6.2")
    v = cascade_verdict(fits)
    missing = [NAMES[k] for k in TABLE_6_2 if k not in fits]
    if missing:
        v = Verdict(UNRESOLVED, f"no fit for {', '.join(missing)}; at face value: {v.verdict}, "
                    f"{v.reason}", v.null, v.alternative, v.power, v.scale_, v.power_at)
    if levels and levels != {LEVELS}:
        v = Verdict(UNRESOLVED, f"the cascades ran {'/'.join(map(str, sorted(levels)))} levels where "
                    f"the thesis ran {LEVELS}; at face value: {v.verdict}, {v.reason}", v.null,
                    v.alternative, v.power, v.scale_, v.power_at)
    v.reason += ("; D_f fitted as A k^(−D_f) on |n| = kL/2π ∈ [4, 32] (the thesis gives no range); "
                 "the symmetrised cascade, which the thesis could not fit, has S(k) = 0 on the axes")

    def draw(ax):
        ks = list(TABLE_6_2)
        x = np.arange(len(ks))
        ax.errorbar(x - 0.1, [TABLE_6_2[k][0] for k in ks], [TABLE_6_2[k][1] for k in ks], fmt="s",
                    color="C3", mfc="none", capsize=4, label="thesis Table 6.2, ± its error")
        f = [(i, fits[k]) for i, k in enumerate(ks) if k in fits]
        ax.errorbar([i + 0.1 for i, _ in f], [q[0] for _, q in f], [1.96 * q[1] for _, q in f],
                    fmt="o", color="C0", capsize=4, label="gransim fit, 95 %")
        ax.plot([i + 0.1 for i, q in f if q[2] is not None], [q[2] for _, q in f if q[2] is not None],
                "k_", ms=14, label="exact correlation dimension D₂")
        ax.axhspan(1.60, 1.66, color="grey", alpha=0.15, label="RFM: 1.60…1.66")
        _ax(ax, "multiplicative cascades, 8 levels (thesis Table 6.2)", "process", "D_f", fs=7)
        ax.set_xticks(x, [NAMES[k] for k in ks])  # after _ax, whose axis scales reset the ticks
    return dict(measured="D_f = " + ", ".join(f"{_ci(q[0], q[1])} ({NAMES[k]})" for k, q in fits.items())
                + " (95 %)", verdict=v, chart=_chart(d, "cascade", draw),
                values={f"D_f_{k}": q[0] for k, q in fits.items()})


def fluid_claims(t2, t3, t5):
    """rfm.CLAIMS' entries of the 2D fluid against φ (rfm_fluid) and the auxiliary models, under
    rfm's topics t2 (2D structure), t3 (velocities) and t5 (models)"""
    return [
        ("g-R", t2, "g(R) which weakly decays, for large distance R such that g(R) appears nearly "
         "constant […] The dashed line is a constant fit of 0.98", "§4.2, Fig. 4.7 (φ = 0.530, "
         "L = 0.4 m, ε = 0.1); eq. 4.14", c_gr,
         ("standard", "the thesis' L = 0.4 m at φ = 0.530 (N = 12000), 2 s sampled")),
        ("moments-phi", t3, "For low packing fraction of less than 0.1 all measured orders of the "
         "moments of velocity obey the expected mean field prediction of ⟨|v|^m⟩^{3/m} ∝ 1/ϕ",
         "§5.1, eq. 5.3, Fig. 5.2 (m = 3, 6, 9, 12; ε = 0.1)", c_moments_phi,
         ("full", "two points below φ = 0.1 (N = 100 and 500 at L = 0.2 m)")),
        ("alpha-phi", t3, "\"the ranges of α that are accepted\" at ε = 0.1, L = 0.2 m: 1.53 ± 0.08 "
         "(ϕ = 0.088), 1.45 ± 0.05 (0.177), 1.30 ± 0.10 (0.353), 1.18 ± 0.03 (0.707)",
         "§5.1.1–5.1.2, Tables 5.1–5.2", c_alpha_phi, ("standard", "φ = 0.088…0.707, 4 s sampled")),
        ("crossover", t3, "ε_n, ε_t = 0.1, 0.1: v_r = 0.168, v_c/v_r = 1.524 (fits of "
         "P₀(v) = D exp(−(v/v_r)²/(1 + |v/v_c|^{2−α})), α = 1.00)", "§5.3.4, eq. 5.32, Tables 5.3–5.4",
         c_crossover, ("standard", "Table 5.3's system, L = 0.4 m and N = 12000 at φ = 0.530")),
        ("spm-alpha", t5, "α = 6(D_f − 1)/(3D_f − 1) ≈ 3.78/3.89 ≈ 0.972 ± 0.03", "§5.3.2, eq. 5.29",
         c_spm_alpha, ("standard", "D_f from 15 s of S(k)")),
        ("spm-pv", t5, "Agreement between the model and representation is remarkably good over many "
         "decades of P(v) which demonstrates that the Single Particle Model gets the high velocity "
         "behaviour of the particles correct", "§5.2.3, Fig. 5.10 (L = 0.6 m, φ = 0.530, ε = 0.1)",
         c_spm_pv, ("standard", "the model on each seed's free paths of the L = 0.6 m fluid")),
        ("cascade", t5, "UCP 1.602 ± 0.066, UnonCP 1.595 ± 0.064, Meakin 1 1.287 ± 0.084, Meakin 2 "
         "1.596 ± 0.147, Meakin 3 1.828 ± 0.233, Meakin 4 1.689 ± 0.178", "§6.2.2, Table 6.2 (8 levels)",
         c_cascade, ("standard", "500 realisations, run after the sweeps into DIR/models/cascade")),
    ]

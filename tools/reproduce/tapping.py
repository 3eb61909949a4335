"""The tapping paper's claims (Becker & Kassner 2015) against a `gransim reproduce tapping` run.
Each function reads the analysis, decides a verdict with verdicts.py and draws its chart."""
import math
import os

import matplotlib.pyplot as plt
import numpy as np

from report import Claim
from tapping_data import (Study, block_bootstrap, column, quadron_phi, sigma_err,
                          steady_window, taps_needed)
from verdicts import (AGREES, DISAGREES, UNRESOLVED, below_bound, chi2_consistent,
                      compare_value, extremum, mean_err, step_change)

NEG, ROT = "negative_g", "rotating_g"
NEXT = {"smoke": "quick", "quick": "standard", "standard": "full", "full": "more taps than the paper's"}


def _save(study, fig, name):
    rel = os.path.join("charts", name + ".png")
    fig.tight_layout()
    fig.savefig(os.path.join(study.folder, rel), dpi=90)
    plt.close(fig)
    return rel


def _finish(st, fig, ax, xlabel, ylabel, name, fontsize=8, ncol=1):
    """label the axes, add the legend and save the chart; its path relative to the report"""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=fontsize, ncol=ncol)
    return _save(st, fig, name)


def _fig(w=6.4, h=3.8):
    return plt.subplots(figsize=(w, h))


def _pm(v, e, d=4):
    return f"{v:.{d}f} ± {1.96 * e:.{d}f}" if math.isfinite(e) else f"{v:.{d}f}"


def transient(st, budget):
    """Fig. 4: the steady state within ~10 taps"""
    worst, rows = 0.0, []
    fig, ax = _fig()
    for r in st.runs():
        lab = r["label"]
        (w, ew), (m, em) = steady_window(lab, st, 6, 10)
        if not (math.isfinite(w) and math.isfinite(m)):
            continue
        z = (w - m) / math.hypot(ew, em)
        rows.append((lab, z))
        worst = max(worst, abs(z))
        taps = st.taps(lab)
        ax.plot(column(taps, "tap"), column(taps, "phi") - m, lw=0.8, label=lab)
    ax.axvline(10, color="k", ls="--", lw=1, label="paper: steady after < 10 taps")
    chart = _finish(st, fig, ax, "tap", "φ − steady φ̄", "transient", 6, ncol=2)
    if not rows:
        v, why = UNRESOLVED, "no run has taps 6–10 and a steady part"
    elif worst <= 3.0:
        v, why = AGREES, f"taps 6–10 lie within {worst:.1f}σ of the steady mean in all {len(rows)} runs"
    elif worst > 4.0:
        lab = max(rows, key=lambda t: abs(t[1]))[0]
        v, why = DISAGREES, f"taps 6–10 of {lab} are {worst:.1f}σ from its steady mean"
    else:
        v, why = UNRESOLVED, f"taps 6–10 lie up to {worst:.1f}σ from the steady mean"
    return Claim("steady-state", "Transient", "The mean volume fraction reaches a steady state "
                 "value very quickly (after approximately < 10 taps)", "Fig. 4, section IV",
                 "(mean of taps 6–10 − steady φ̄)/σ per run: "
                 + "; ".join(f"{lab} {z:+.1f}" for lab, z in rows),
                 v, why, "" if v != UNRESOLVED else f"the {NEXT[budget]} budget", chart,
                 {"max_z": worst})


def _curve(st, protocol, key):
    rows = st.runs(protocol)
    x = column(rows, "control")
    if key == "phi":
        return x, column(rows, "phi_mean"), column(rows, "phi_err")
    return x, column(rows, "sigma"), np.array([sigma_err(r) for r in rows])


def neg_minimum(st, budget):
    """Fig. 5a: φ̄(g_p) falls to a minimum near g_p ≈ 20 and rises beyond it"""
    x, y, e = _curve(st, NEG, "phi")
    sig = np.nanmedian(column(st.runs(NEG), "sigma")) if len(x) else float("nan")
    effect = 0.5 * sig if math.isfinite(sig) else 0.0
    (v, why), at = extremum(x, y, e, "min", expect_at=20.0, min_effect=effect)
    fig, ax = _fig()
    ax.errorbar(x, y, yerr=1.96 * e, fmt="o-", capsize=3, label="gransim (95 % CI, τ-corrected)")
    ax.axvspan(16, 24, color="tab:orange", alpha=0.2, label="paper: minimum near g_p ≈ 20")
    chart = _finish(st, fig, ax, "g_p", "φ̄", "neg_phi_mean", 8)
    meas = "; ".join(f"g_p={xi:g}: {_pm(yi, ei)}" for xi, yi, ei in zip(x, y, e))
    return Claim("neg-minimum", "Negative g", "the volume fraction decreases with increasing pulse "
                 "strength until it reaches a local minimum around g_p = 20. Afterwards, the "
                 "volume fraction increases with the pulse strength.", "Fig. 5a, section IV",
                 meas, v, why + f" (a dip must be ≥ {effect:.4f}, half the median σ_φ, to count)",
                 "" if v != UNRESOLVED else f"the {NEXT[budget]} budget (more taps and g_p values)",
                 chart, {"minimum_at": at if at is not None else float("nan")}), at


def neg_sigma_maximum(st, budget, at):
    """Fig. 5b: σ_φ has a local maximum where φ̄ is minimal"""
    x, y, e = _curve(st, NEG, "sigma")
    where = at if at is not None else 20.0
    effect = 0.15 * np.nanmedian(y) if len(y) else 0.0
    (v, why), mx = extremum(x, y, e, "max", expect_at=where, min_effect=effect)
    fig, ax = _fig()
    ax.errorbar(x, y, yerr=1.96 * e, fmt="s-", capsize=3, color="tab:red", label="gransim σ_φ")
    ax.axvline(where, color="k", ls="--", lw=1,
               label=f"minimum of φ̄ ({'measured' if at is not None else 'paper'}: {where:g})")
    chart = _finish(st, fig, ax, "g_p", "σ_φ", "neg_sigma", 8)
    meas = "; ".join(f"g_p={xi:g}: {_pm(yi, ei, 5)}" for xi, yi, ei in zip(x, y, e))
    return Claim("neg-sigma-maximum", "Negative g", "At the same value of g_p, where the volume "
                 "fraction is minimal, the volume fraction fluctuations have a local maximum",
                 "Fig. 5b, section IV", meas, v, why + f" (a peak must be ≥ {effect:.5f}, 15 % of "
                 "the median σ_φ, to count)", "" if v != UNRESOLVED else
                 "the standard budget or more: σ_φ needs hundreds of taps per value (the paper: "
                 "'some hundred taps' were not enough)", chart,
                 {"maximum_at": mx if mx is not None else float("nan")})


def rot_crossover(st, budget):
    """Fig. 6a: φ̄(f) crosses over from ≈ 0.814 to ≈ 0.821"""
    x, y, e = _curve(st, ROT, "phi")
    step = step_change(x, y, e, 0.821 - 0.814)
    fig, ax = _fig()
    ax.errorbar(x, y, yerr=1.96 * e, fmt="D-", capsize=3, label="gransim")
    ax.axhline(0.814, color="tab:orange", ls=":", label="paper: ≈ 0.814 (low f)")
    ax.axhline(0.821, color="tab:green", ls=":", label="paper: ≈ 0.821 (high f)")
    chart = _finish(st, fig, ax, "f (Hz)", "φ̄", "rot_phi_mean", 8)
    meas = "; ".join(f"f={xi:g} Hz: {_pm(yi, ei)}" for xi, yi, ei in zip(x, y, e))
    claims = [Claim("rot-crossover", "Rotating g", "With increasing frequency the mean volume "
                    "fraction shows a crossover from φ̄ ≃ 0.814 to φ̄ ≃ 0.821", "Fig. 6a, section IV",
                    meas, step.verdict, step.reason, "" if step.verdict != UNRESOLVED else
                    f"the {NEXT[budget]} budget", chart)]
    if len(x) >= 2:
        lo = compare_value(y[0], e[0], 0.814, tolerance=0.0005)
        hi = compare_value(y[-1], e[-1], 0.821, tolerance=0.0005)
        vs = {lo.verdict, hi.verdict}
        v = DISAGREES if DISAGREES in vs else (AGREES if vs == {AGREES} else UNRESOLVED)
        claims.append(Claim("rot-levels", "Rotating g", "φ̄ ≃ 0.814 at low frequency, φ̄ ≃ 0.821 "
                            "at high frequency", "Fig. 6a, section IV",
                            f"f={x[0]:g} Hz: {_pm(y[0], e[0])}; f={x[-1]:g} Hz: {_pm(y[-1], e[-1])}",
                            v, f"low f: {lo.reason}; high f: {hi.reason}", "", chart,
                            {"phi_low_f": y[0], "phi_high_f": y[-1]}))
    return claims


def halves(st, budget):
    """section IV: the two columns of the test square against the whole"""
    mean_rows, ratio_rows = [], []
    for r in st.runs():
        lab = r["label"]
        pl, pr, p = (st.used(lab, k) for k in ("phi_left", "phi_right", "phi"))
        if len(p) < 10 or not np.all(np.isfinite(pl)):
            continue
        rel = (pl - p) / p
        m, e = mean_err(rel)
        mean_rows.append((lab, abs(m), e, len(p)))
        ratio = 0.5 * (np.std(pl, ddof=1) + np.std(pr, ddof=1)) / np.std(p, ddof=1)
        re = block_bootstrap([p, pl, pr], lambda a, b, c: 0.5 * (np.std(b, ddof=1) + np.std(c, ddof=1))
                             / np.std(a, ddof=1))
        ratio_rows.append((lab, ratio, re, len(p)))
    out = []
    for rows, cid, bound, quote, unit in (
            (mean_rows, "halves-mean", 1e-4, "The relative difference of mean volume fraction "
             "(after 2500 taps) between the columns and the entire test volume was always smaller "
             "than 0.01 %", "relative difference"),
            (ratio_rows, "halves-sigma", 0.01, "the deviation of the volume fraction fluctuation "
             "ratio from √2 was always lower than 1 %", "|ratio/√2 − 1|")):
        if not rows:
            out.append(Claim(cid, "Test volume", quote, "section IV", "no run with φ_left, φ_right",
                             UNRESOLVED, "no data"))
            continue
        verdicts = []
        for lab, val, err, n in rows:
            q = abs(val / math.sqrt(2) - 1) if cid == "halves-sigma" else val
            qe = err / math.sqrt(2) if cid == "halves-sigma" else err
            verdicts.append((below_bound(q, qe, bound), lab, q, qe, n))
        vs = {t[0].verdict for t in verdicts}
        v = DISAGREES if DISAGREES in vs else (AGREES if vs == {AGREES} else UNRESOLVED)
        worst = max(verdicts, key=lambda t: t[2] + 2 * t[3])
        n_min = min(t[4] for t in verdicts)
        if v == DISAGREES and n_min < 1000:
            # the bound is on 2500-tap means: a left–right difference that outlives a short
            # series (the pile's memory of its preparation) is not in a short series' error
            v = UNRESOLVED
            note = (f"; the paper's bound holds after 2500 taps, these runs have {n_min:.0f}: a "
                    "left–right difference that lasts longer than the series is not in its error")
        else:
            note = ""
        need = max(taps_needed(t[4], t[3], bound / 2) for t in verdicts)
        fig, ax = _fig()
        labs = [t[1] for t in verdicts]
        ax.errorbar(range(len(labs)), [t[2] for t in verdicts], yerr=[1.96 * t[3] for t in verdicts],
                    fmt="o", capsize=3, label="gransim")
        ax.axhline(bound, color="tab:orange", ls="--", label=f"paper: < {bound:g}")
        ax.set_xticks(range(len(labs)), labs, rotation=45, ha="right", fontsize=7)
        ax.set_ylabel(unit)
        ax.legend(fontsize=8)
        chart = _save(st, fig, cid)
        out.append(Claim(cid, "Test volume", quote, "section IV",
                         f"largest {unit}: {worst[2]:.2g} ± {1.96 * worst[3]:.2g} ({worst[1]}); "
                         f"{len(rows)} runs", v,
                         f"{sum(t[0].verdict == AGREES for t in verdicts)} of {len(rows)} runs "
                         f"below the bound at 95 %; worst: {worst[0].reason}{note}",
                         "" if v != UNRESOLVED else f"≈ {need:.0f} taps per value",
                         chart, {"worst": worst[2], "worst_err": worst[3]}))
    return out


def normality(st, budget):
    """section V: the χ² test rejects normality for every sample"""
    rows = st.runs()
    rej = [r for r in rows if r.get("normal") == 0]
    n_min = min((r["n_used"] for r in rows), default=0)
    if rows and len(rej) == len(rows):
        v, why = AGREES, f"normality rejected at 5 % in all {len(rows)} runs"
    elif n_min >= 2000:
        v, why = DISAGREES, f"normality kept in {len(rows) - len(rej)} of {len(rows)} runs of ≥ 2000 taps"
    else:
        v, why = UNRESOLVED, (f"rejected in {len(rej)} of {len(rows)} runs, with {n_min:.0f}+ taps: "
                              "the paper's own test runs of ≈ 100 taps did not reject it either [57]")
    return Claim("normality", "Distributions", "The null hypothesis that the data is normally "
                 "distributed was rejected for all samples", "section V and note [57]",
                 f"χ² test p-values: " + ", ".join(f"{r['label']} {r['chi2_p']:.2g}" for r in rows),
                 v, why, "" if v != UNRESOLVED else "the full budget (≥ 2500 taps per value)")


def q_linear(st, budget):
    """Figs. 7b, 8b: Q(1/φ) is a straight line for overlapping pairs"""
    rows = [r for r in st.primary_beta() if r.get("valid") == 1 and r.get("label") != st.info.get("reference")]
    ok = [r for r in rows if math.isfinite(r.get("quad_err", float("nan")))]
    (v, why), _ = chi2_consistent(column(ok, "quad"), column(ok, "quad_err"), "curvature coefficients")
    slopes = [abs(r["dbeta"] / r["dbeta_err"]) for r in rows if r.get("dbeta_err", 0) > 0]
    if v == AGREES and not any(s > 3 for s in slopes):
        v, why = UNRESOLVED, why + "; but no slope is resolved (|β̂/σ| < 3), so a line is not shown"
    fig, ax = _fig()
    ref = st.info.get("reference")
    for lab in sorted({r["label"] for r in st.q_lines if r["reference"] == ref and r["label"] != ref}):
        pts = [r for r in st.q_lines if r["reference"] == ref and r["label"] == lab]
        x = column(pts, "inv_phi")
        ax.errorbar(x, column(pts, "q"), yerr=column(pts, "q_err"), fmt=".", ms=3)
        ax.plot(x, column(pts, "q_line"), lw=1, label=lab)
    chart = _finish(st, fig, ax, "1/φ", f"Q = ln(P/P_ref), ref {ref}", "q_lines", 6, ncol=2)
    return Claim("q-linear", "Overlapping histograms", "we always found a linear relation between "
                 "Q and the inverse volume fraction φ⁻¹", "Figs. 7b, 8b, section V",
                 f"{len(rows)} runs overlap the reference {ref}; curvature test {why.split(';')[0]}",
                 v, why, "" if v != UNRESOLVED else f"the {NEXT[budget]} budget", chart)


def reference_overlap(st, budget):
    """section V: the g_p = 6 distribution overlaps every other one (it is the reference)"""
    ref = next((r for r in st.runs(NEG) if r["control"] == 6), None)
    if ref is None:
        return Claim("reference-overlap", "Overlapping histograms", "the distribution with g_p = 6 "
                     "… has sufficient overlap with all the other distributions", "section V",
                     "no run at g_p = 6", UNRESOLVED, "the plan has no g_p = 6 run")
    rows, apart = [], []
    for r in st.runs():
        if r["label"] == ref["label"]:
            continue
        # separation of the two distributions in units of their spreads
        sep = abs(r["phi_mean"] - ref["phi_mean"]) / math.hypot(r["sigma"], ref["sigma"])
        rows.append((r["label"], sep))
        if sep > 4.0:
            apart.append(r["label"])
    worst = max((x[1] for x in rows), default=float("nan"))
    if not rows:
        v, why = UNRESOLVED, "no other run"
    elif apart:
        v, why = DISAGREES, (f"{len(apart)} of {len(rows)} distributions lie more than 4 spreads "
                             f"from g_p = 6 (√(σ²+σ_ref²)): {', '.join(apart)}; they cannot overlap it")
    elif worst < 2.0:
        v, why = AGREES, f"every distribution lies within 2 spreads of g_p = 6 (largest {worst:.1f})"
    else:
        v, why = UNRESOLVED, f"the largest separation is {worst:.1f} spreads"
    fig, ax = _fig()
    for r in st.runs():
        ax.errorbar([r["phi_mean"]], [r["control"] if r["protocol"] == NEG else -r["control"]],
                    xerr=[r["sigma"]], fmt="s" if r["protocol"] == NEG else "D", capsize=3,
                    color="k" if r["label"] == ref["label"] else None, label=r["label"])
    chart = _finish(st, fig, ax, "φ̄ ± σ_φ (the spread of each distribution)", "g_p (negative g) / −f in Hz (rotating g)", "reference_overlap", 6, ncol=2)
    return Claim("reference-overlap", "Overlapping histograms", "the distribution with g_p = 6 of "
                 "the “negative g” protocol was chosen as the reference distribution, because it "
                 "has sufficient overlap with all the other distributions", "section V, Figs. 7b, 8b",
                 "separation from g_p = 6 in spreads: " + "; ".join(f"{l} {x:.1f}" for l, x in rows),
                 v, why, "" if v != UNRESOLVED else f"the {NEXT[budget]} budget", chart,
                 {"largest_separation": worst})


def two_references(st, budget):
    """Fig. 7c: β̂ from two references differ by a constant"""
    off = st.info.get("reference_offset", {})
    chi2, dof = off.get("chi2"), off.get("dof", 0)
    if chi2 is None or not dof or dof < 2:
        v, why, p = UNRESOLVED, "fewer than 3 runs overlap both references", float("nan")
    else:
        from verdicts import chi2_sf
        p = chi2_sf(chi2, dof)
        v = AGREES if p > 0.05 else (DISAGREES if p < 0.01 else UNRESOLVED)
        why = f"χ² = {chi2:.1f} for {dof} degrees of freedom (p = {p:.3g}) around a constant offset"
    fig, ax = _fig()
    for ref, mk in ((st.info.get("reference"), "s"), (st.info.get("reference2"), "o")):
        rows = [r for r in st.beta if r.get("reference") == ref and r.get("valid") == 1]
        shift = off.get("dbeta", 0.0) if ref == st.info.get("reference2") else 0.0
        ax.errorbar(column(rows, "phi_mean"), column(rows, "dbeta") + (shift or 0.0),
                    yerr=1.96 * column(rows, "dbeta_err"), fmt=mk, capsize=2,
                    label=f"reference {ref}" + (" (+ offset)" if shift else ""))
    chart = _finish(st, fig, ax, "φ̄", "β̂ (1/m²)", "two_references", 8)
    return Claim("two-references", "Overlapping histograms", "the values determined for β using "
                 "different samples as reference distribution may only differ by an additive "
                 "constant", "Fig. 7c, eq. (39)",
                 (f"offset {off.get('dbeta'):.4g} ± {1.96 * off.get('err'):.2g} 1/m², χ² {chi2:.1f} "
                  f"for {dof} d.o.f." if v != UNRESOLVED or (dof and dof >= 2) else
                  "no second reference with ≥ 3 common runs"), v, why,
                 "" if v != UNRESOLVED else f"the {NEXT[budget]} budget", chart, {"p": p})


def _fit(st):
    """the quadron fit over every run: the joint multiple-histogram β̂ where it converged"""
    fits = st.quadron.get("fits", {})
    for name in ("joint", "all"):
        f = fits.get(name)
        if f and f.get("converged"):
            return name, f
    return None, None


def quadron_claims(st, budget):
    """Figs. 9–11: one β(φ̄) curve, the ideal-quadron fit and what it predicts"""
    out = []
    name, fit = _fit(st)
    lim = (st.quadron.get("phi_rlp", 0.81), st.quadron.get("phi_rcp", 0.855))
    mult = {r["label"]: r for r in st.beta_multi}
    nxt = f"the {NEXT[budget]} budget"
    if fit is None:
        why = "the ideal-quadron fit did not converge (too few runs with β̂)"
        for cid, q, where in (
                ("one-curve", "All the data, whether obtained from the branch left of the minimum "
                 "or the branch right of the minimum … or else from the “rotating g” protocol, "
                 "fall on one curve", "Fig. 9, section V"),
                ("quadron-a", "we find as fitting value N z̄/V_g = 556.51 m⁻²", "Fig. 9, section V"),
                ("protocol-fits", "The relative deviation of the obtained fitting parameters is "
                 "smaller than 2%", "section V"),
                ("lnz", "the numerically determined values and the ideal quadron solution fit "
                 "very well", "Fig. 10"),
                ("sigma-phi", "The data is in good agreement with the fit", "Fig. 11")):
            out.append(Claim(cid, "Edwards statistics", q, where, "no fit", UNRESOLVED, why, nxt))
        return out
    a, b0 = fit["a"], fit["beta0"]

    # one curve: φ̄ against the fit at each run's β̂, grouped by protocol and branch
    at = None
    neg = st.runs(NEG)
    if len(neg) >= 3:
        i = int(np.argmin(column(neg, "phi_mean")))
        at = neg[i]["control"]
    groups, resid = {}, []
    for r in st.summary:
        m = mult.get(r["label"])
        use_joint = name == "joint"
        if m is None or not (m["joint_valid" if use_joint else "direct_valid"] == 1):
            continue
        bh = m["joint_dbeta" if use_joint else "direct_dbeta"]
        be = m["joint_dbeta_err" if use_joint else "direct_dbeta_err"]
        try:
            pf = quadron_phi(bh + b0, a, *lim)
            dp = (quadron_phi(bh + b0 + 1.0, a, *lim) - pf)
        except (ZeroDivisionError, ValueError, OverflowError):
            continue
        e = math.hypot(r["phi_err"], dp * (be if math.isfinite(be) else 0.0))
        g = r["protocol"] if r["protocol"] == ROT or at is None else (
            f"{NEG} g_p ≤ {at:g}" if r["control"] <= at else f"{NEG} g_p > {at:g}")
        groups.setdefault(g, []).append((r["phi_mean"] - pf, e))
        resid.append((r["phi_mean"], bh + b0, r["protocol"]))
    gm, ge, names = [], [], []
    for g, v in groups.items():
        w = np.array([1 / x[1] ** 2 for x in v])
        gm.append(float(np.sum(w * np.array([x[0] for x in v])) / w.sum()))
        ge.append(float(1 / math.sqrt(w.sum())))
        names.append(g)
    (v, why), _ = chi2_consistent(gm, ge, "group mean residuals")
    if v == AGREES and (not fit.get("a_err") or fit["a_err"] > 0.5 * a):
        v, why = UNRESOLVED, why + f"; but the fit's N z̄/V_g is barely determined ({a:.0f} ± {fit.get('a_err', float('nan')):.0f})"
    fig, ax = _fig()
    for proto, mk in ((NEG, "s"), (ROT, "D")):
        pts = [(p, b) for p, b, pr in resid if pr == proto]
        if pts:
            ax.plot([p for p, _ in pts], [b for _, b in pts], mk, label=f"gransim {proto}")
    curve = fit.get("curve", {})
    if curve.get("phi"):
        ax.plot(curve["phi"], np.array(curve["beta_hat"]) + b0, "k-", lw=1,
                label=f"ideal quadron fit, N z̄/V_g = {a:.0f} m⁻²")
    chart = _finish(st, fig, ax, "φ̄", "β = β̂ + β₀ (1/m²)", "beta_phi", 8)
    out.append(Claim("one-curve", "Edwards statistics", "All the data, whether obtained from the "
                     "branch left of the minimum or the branch right of the minimum in the φ(g_p) "
                     "curve … or else from the “rotating g” protocol, [fall on one curve]",
                     "Fig. 9, section V", "mean residual φ̄ − φ_quadron(β̂ + β₀) per group: " +
                     "; ".join(f"{n} {m:+.4f} ± {1.96 * e:.4f}" for n, m, e in zip(names, gm, ge)),
                     v, why + f" (β̂ from the {'joint multiple-histogram' if name == 'joint' else 'direct'} fit)",
                     "" if v != UNRESOLVED else nxt, chart))

    # N z̄/V_g of the fit over every run
    c = compare_value(a, fit.get("a_err", float("nan")), 556.51, fmt="{:.4g}")
    out.append(Claim("quadron-a", "Edwards statistics", "we find as fitting value N z̄/V_g = "
                     "556.51 m⁻²", "Fig. 9, eq. (26), section V",
                     f"N z̄/V_g = {a:.4g} ± {1.96 * fit.get('a_err', float('nan')):.3g} m⁻², "
                     f"β₀ = {b0:.4g} 1/m² ({name} fit, φ_rlp = {lim[0]}, φ_rcp = {lim[1]})",
                     c.verdict, c.reason, "" if c.verdict != UNRESOLVED else nxt, chart,
                     {"a": a, "a_err": fit.get("a_err"), "beta0": b0}))

    # fits to one protocol alone
    fits = st.quadron.get("fits", {})
    fn, fr = fits.get(NEG, {}), fits.get(ROT, {})
    if fn.get("converged") and fr.get("converged"):
        rel = abs(fn["a"] - fr["a"]) / a
        err = math.hypot(fn.get("a_err", 0), fr.get("a_err", 0)) / a
        bb = below_bound(rel, err, 0.02)
        out.append(Claim("protocol-fits", "Edwards statistics", "When we used only the data "
                         "obtained by one of the protocols … The relative deviation of the "
                         "obtained fitting parameters is smaller than 2%", "section V",
                         f"N z̄/V_g: negative g {fn['a']:.4g} ± {1.96 * fn.get('a_err', 0):.3g}, "
                         f"rotating g {fr['a']:.4g} ± {1.96 * fr.get('a_err', 0):.3g} m⁻²",
                         bb.verdict, bb.reason, "" if bb.verdict != UNRESOLVED else nxt))
    else:
        out.append(Claim("protocol-fits", "Edwards statistics", "The relative deviation of the "
                         "obtained fitting parameters is smaller than 2%", "section V",
                         "a protocol's own fit did not converge", UNRESOLVED,
                         "each protocol needs ≥ 3 runs with β̂ for its own fit", nxt))

    # ln Z and σ_φ against the fit's predictions (direct β̂, as beta.csv carries them)
    prim = [r for r in st.primary_beta() if r.get("valid") == 1]
    for cid, key, qkey, ekey, quote, where, lab in (
            ("lnz", "dlnz", "dlnz_quadron", "dlnz_err", "the numerically determined values and the "
             "ideal quadron solution fit very well, independently of the protocol and of the "
             "branch", "Fig. 10, eq. (21)", "Δln Z"),
            ("sigma-phi", "sigma", "sigma_quadron", None, "The data is in good agreement with the "
             "ideal quadron fit", "Fig. 11, eqs. (17), (26)", "σ_φ")):
        rows = [r for r in prim if math.isfinite(r.get(qkey, float("nan")))]
        res = column(rows, key) - column(rows, qkey)
        err = column(rows, ekey) if ekey else np.array([sigma_err(r) for r in rows])
        (v, why), _ = chi2_consistent(res, err, "runs")
        fig, ax = _fig()
        ax.errorbar(column(rows, "phi_mean"), column(rows, key), yerr=1.96 * err, fmt="o",
                    capsize=2, label="gransim")
        ax.plot(column(rows, "phi_mean"), column(rows, qkey), "kx", label="ideal quadron fit")
        ch = _finish(st, fig, ax, "φ̄", lab, cid, 8)
        out.append(Claim(cid, "Edwards statistics", quote, where,
                         f"{len(rows)} runs against the fit's prediction", v, why,
                         "" if v != UNRESOLVED else nxt, ch))
    return out


def stress(st, budget):
    """Fig. 12: the stress tensor is not a unique function of φ̄"""
    pts = []
    for r in st.runs():
        lab = r["label"]
        comp = {k: mean_err(st.used(lab, k)) for k in ("S_xx", "S_yy", "S_xy")}
        if all(math.isfinite(v[0]) for v in comp.values()):
            pts.append((r["protocol"], r["phi_mean"], comp))
    fig, ax = _fig()
    verdicts = []
    for k, col in (("S_xx", "tab:blue"), ("S_yy", "tab:red"), ("S_xy", "tab:green")):
        for proto, mk in ((NEG, "D"), (ROT, "x")):
            sel = [p for p in pts if p[0] == proto]
            if sel:
                ax.errorbar([p[1] for p in sel], [p[2][k][0] for p in sel],
                            yerr=[1.96 * p[2][k][1] for p in sel], fmt=mk, color=col,
                            label=f"{k} {proto}")
        if len(pts) >= 5:
            x = np.array([p[1] for p in pts])
            y = np.array([p[2][k][0] for p in pts])
            e = np.array([p[2][k][1] for p in pts])
            c = np.polyfit(x - x.mean(), y, 2, w=1 / e)
            res = y - np.polyval(c, x - x.mean())
            chi = float(np.sum((res / e) ** 2))
            from verdicts import chi2_sf
            verdicts.append((k, chi2_sf(chi, len(x) - 3), float(np.sqrt(np.mean(res ** 2)))))
    chart = _finish(st, fig, ax, "φ̄", "S_ab (N·m)", "stress", 6, ncol=2)
    if not verdicts:
        v, why = UNRESOLVED, "fewer than 5 runs"
    else:
        pmin = min(p for _, p, _ in verdicts)
        rms = max(r for _, _, r in verdicts)
        desc = "; ".join(f"{k}: p = {p:.2g}, rms scatter {r:.3g} N·m" for k, p, r in verdicts)
        if pmin < 0.01:
            v, why = AGREES, f"the runs do not lie on one smooth curve S(φ̄) (quadratic): {desc}"
        elif all(p > 0.05 for _, p, _ in verdicts):
            v, why = DISAGREES, f"every component is consistent with one curve S(φ̄): {desc}"
        else:
            v, why = UNRESOLVED, desc
    return Claim("stress", "Stress", "The stress tensor is obviously not a unique function of the "
                 "volume fraction … deviations … on the order of 0.01 Nm", "Fig. 12, eq. (41)",
                 f"{len(pts)} runs; " + ("; ".join(f"{k} scatter {r:.3g} N·m" for k, _, r in verdicts)
                                         or "no fit"), v, why,
                 "" if v != UNRESOLVED else f"the {NEXT[budget]} budget", chart)


def segregation(st, budget):
    """section IV: no segregation: the mean heights of big and small grains keep their distance"""
    rows = []
    fig, ax = _fig()
    for r in st.runs():
        taps = st.taps(r["label"])
        if len(taps) < 12 or "z_big" not in taps[0] or "z_small" not in taps[0]:
            continue
        d = (column(taps, "z_big") - column(taps, "z_small")) * 1000.0  # mm
        k = column(taps, "tap")
        m, e = mean_err(d[k > st.discard])
        rows.append((r["label"], m - d[0], e))
        ax.plot(k, d - d[0], lw=0.8, label=r["label"])
    ax.axhline(0, color="k", lw=1, label="paper: no segregation")
    chart = _finish(st, fig, ax, "tap", "Δ(z̄_big − z̄_small) since tap 0 (mm)", "segregation", 6, ncol=2)
    # the distance wanders slowly (over tens of taps), so one run's error from its own taps
    # is too small; the runs are independent: their drifts' mean and scatter decide, against
    # one small grain's radius (6.36 mm) as the smallest segregation that counts
    drifts = np.array([x[1] for x in rows])
    if len(drifts) < 3:
        v, why = UNRESOLVED, "fewer than 3 runs"
    else:
        m = float(drifts.mean())
        se = float(drifts.std(ddof=1) / math.sqrt(len(drifts)))
        why = (f"mean drift over {len(drifts)} runs {m:+.2f} ± {se:.2f} mm (scatter of the runs); "
               "a segregation must exceed one small grain's radius, 6.36 mm")
        if abs(m) + 2 * se < 6.36:
            v = AGREES
        elif abs(m) - 2 * se > 6.36:
            v = DISAGREES
        else:
            v = UNRESOLVED
    return Claim("segregation", "Segregation", "no segregation (big and small grains stay mixed "
                 "from tap to tap)", "section IV (segregation check)",
                 "drift of z̄_big − z̄_small after the transient, mm: " +
                 "; ".join(f"{l} {d:+.2f} ± {1.96 * e:.2f}" for l, d, e in rows),
                 v, why, "" if v != UNRESOLVED else f"the {NEXT[budget]} budget", chart)


def claims(folder, budget):
    st = Study(folder)
    if not st.summary:
        raise SystemExit(f"reproduce_report: {folder}/analysis/summary.csv is missing or empty")
    out = [transient(st, budget)]
    c, at = neg_minimum(st, budget)
    out += [c, neg_sigma_maximum(st, budget, at)]
    out += rot_crossover(st, budget)
    out += halves(st, budget)
    out += [normality(st, budget), reference_overlap(st, budget), q_linear(st, budget),
            two_references(st, budget)]
    out += quadron_claims(st, budget)
    out += [stress(st, budget), segregation(st, budget)]
    runs = st.runs()
    taps = ", ".join(f"{r['label']} {r['n_used']:.0f}" for r in runs)
    notes = [f"Taps used per run after the first {st.discard}: {taps}.",
             "Errors are standard errors with the integrated autocorrelation time (n_eff = n/2τ); "
             "intervals are 95 %. β̂ of runs that do not overlap the reference come from the joint "
             "multiple-histogram fit (analysis/beta_multi.csv, beside the direct and chained "
             "estimates)."]
    intro = ("The tapping paper (V. Becker and K. Kassner, Protocol-independent granular "
             "temperature supported by numerical simulations, 2015) against gransim's runs of the "
             "same pile: 1184 bidisperse decagons, the paper's force law and protocols, velocity "
             "Verlet at Δt = 1/7500 s with early rest (docs/tapping.md). The pulse is read as g_p·g "
             "for t1 = 0.01 s (docs/physics.md). Every verdict is computed from the data.")
    return "Reproduction of the tapping study", intro, out, notes

"""The tapping paper's Edwards-statistics claims (overlapping histograms, β, ln Z, the ideal
quadron fit) against a `gransim reproduce tapping` run."""
import math

import numpy as np

from report import Claim
from tapping_data import NEG, NEXT, ROT, _fig, _finish, column, quadron_phi, sigma_err
from verdicts import (AGREES, DISAGREES, UNRESOLVED, below_bound, chi2_consistent, chi2_sf,
                      compare_value)


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
        line = ax.plot(x, column(pts, "q_line"), lw=1, label=lab)[0]
        ax.errorbar(x, column(pts, "q"), yerr=column(pts, "q_err"), fmt="o", ms=4, capsize=2,
                    color=line.get_color())
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

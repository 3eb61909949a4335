"""The tapping paper's Edwards-statistics claims (overlapping histograms, β, ln Z, the ideal
quadron fit) against a `gransim reproduce tapping` run."""
import math

import numpy as np

from .report import Claim, test_of
from .tapping_data import NEG, NEXT, ROT, _fig, _finish, column, phi_errors, quadron_phi
from .tapping_quadron import (A_PAPER, A_PREC, _fit, curve_points, limits, quadron_estimate,
                              residual_cov_inverse)
from .verdicts import (AGREES, DISAGREES, UNRESOLVED, Verdict, below_bound, chi2_consistent,
                      chi2_power, chi2_sf, compare_value, cov_inverse, decide, offset_test,
                      without_covariance)

# the paper's Q is evaluated where each density exceeds 5 % of its maximum (section V); for a
# Gaussian that is |φ − φ̄| < σ√(2 ln 20)
OVERLAP = math.sqrt(2 * math.log(20))


def _need(v, n, unit="taps per value"):
    return v.need(n, unit) if v.verdict == UNRESOLVED else ""


def _n_med(st):
    n = column(st.runs(), "n_used")
    return float(np.nanmedian(n)) if len(n) else float("nan")


# ---- the Gaussian pair of App. A: what φ̄ and σ_φ alone give ------------------------------------
# In x = 1/φ (V = V_g x) a Gaussian run (x₁, s₁) against a Gaussian reference (x₂, s₂) gives
# Q = ln P₁/P₂ with curvature ½(1/s₂² − 1/s₁²) (A1), slope A = ½(1/s₁² + 1/s₂²)(x₁ − x₂) at the
# midpoint (A3), so β̂ = −A/V_g, and an intercept that departs from Edwards' −Δβ·V̄ by
# δ = ⅛(x₂ − x₁)²(1/s₂² − 1/s₁²) + ln(s₂/s₁) (A6 with A3).

def _x(phi, sigma):
    return 1.0 / phi, sigma / phi ** 2


def gauss_curvature(phi1, s1, phi2, s2):
    (_, a), (_, b) = _x(phi1, s1), _x(phi2, s2)
    return 0.5 * (1 / b ** 2 - 1 / a ** 2)


def gauss_dbeta(phi1, s1, phi2, s2, v_g):
    (x1, a), (x2, b) = _x(phi1, s1), _x(phi2, s2)
    return -0.5 * (1 / a ** 2 + 1 / b ** 2) * (x1 - x2) / v_g


def gauss_dlnz_excess(phi1, s1, phi2, s2):
    (x1, a), (x2, b) = _x(phi1, s1), _x(phi2, s2)
    return (x2 - x1) ** 2 * (1 / b ** 2 - 1 / a ** 2) / 8 + math.log(b / a)


# ---- the ideal quadron's σ_φ(φ̄): eq. (17) with (26) ---------------------------------------------

def quadron_beta(phi, a, lim=(0.81, 0.855)):
    """β with φ̄_quadron(β) = φ (φ̄ rises with β between φ_rlp and φ_rcp)"""
    lo, hi = -1e3 * a, 1e3 * a
    if not lim[0] < phi < lim[1]:
        return float("nan")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        b = mid if abs(mid) > 1e-9 * a else 1e-9 * a
        if quadron_phi(b, a, *lim) < phi:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def quadron_sigma(phi, a, v_g, lim=(0.81, 0.855)):
    """σ_φ² = φ̄²/V_g · ∂φ̄/∂β (17) on the ideal quadron curve (26) with N z̄/V_g = a"""
    b = quadron_beta(phi, a, lim)
    if not math.isfinite(b):
        return float("nan")
    h = 1e-4 * a
    b1, b2 = (b - h, b + h) if abs(b) > 2 * h else (b + h, b + 3 * h)
    d = (quadron_phi(b2, a, *lim) - quadron_phi(b1, a, *lim)) / (b2 - b1)
    return math.sqrt(phi ** 2 / v_g * d) if d > 0 else float("nan")


def sigma_peak_effect(st):
    """the σ_φ peak that eq. (17) with the paper's own fit implies at the measured φ̄ dip:
    σ(φ̄_min) − σ(φ̄_min + depth); (None, why) without a dip or V_g"""
    v_g = st.quadron.get("v_g", st.info.get("v_g"))
    neg = st.runs(NEG)
    y = column(neg, "phi_mean")
    if not v_g or len(y) < 3:
        return None, "none: no V_g or fewer than 3 negative-g runs"
    i = int(np.argmin(y[1:-1])) + 1
    depth = min(y[:i].max(), y[i + 1:].max()) - y[i]
    if not depth > 0:
        return None, "none: the measured φ̄ has no interior dip to size the σ_φ peak from"
    lo, hi = quadron_sigma(y[i], A_PAPER, v_g), quadron_sigma(y[i] + depth, A_PAPER, v_g)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return None, "none: the dip lies outside the quadron's φ_rlp…φ_rcp"
    return lo - hi, (f"eq. (17) with the paper's fit N z̄/V_g = {A_PAPER} at the measured φ̄ dip "
                     f"of {depth:.2g}")



def _ref_row(st, label):
    return next((r for r in st.summary if r["label"] == label), None)


def q_linear(st, budget):
    """Figs. 7b, 8b: Q(1/φ) is a straight line for overlapping pairs"""
    ref = st.info.get("reference")
    rr = _ref_row(st, ref)
    rows = [r for r in st.primary_beta() if r.get("valid") == 1 and r.get("label") != ref]
    ok = [r for r in rows if math.isfinite(r.get("quad_err", float("nan")))]
    alt = ([gauss_curvature(r["phi_mean"], r["sigma"], rr["phi_mean"], rr["sigma"]) for r in ok]
           if rr else None)
    v, _ = chi2_consistent(column(ok, "quad"), column(ok, "quad_err"), "curvature coefficients",
                           alternative=alt, alt_text="the curvatures of Gaussian pairs with the "
                           "measured φ̄ and σ_φ (App. A, eq. A1): " +
                           ", ".join(f"{c:.2g}" for c in (alt or [])))
    fig, ax = _fig()
    for lab in sorted({r["label"] for r in st.q_lines if r["reference"] == ref and r["label"] != ref}):
        pts = [r for r in st.q_lines if r["reference"] == ref and r["label"] == lab]
        x = column(pts, "inv_phi")
        line = ax.plot(x, column(pts, "q_line"), lw=1, label=lab)[0]
        ax.errorbar(x, column(pts, "q"), yerr=column(pts, "q_err"), fmt="o", ms=4, capsize=2,
                    color=line.get_color())
    chart = _finish(st, fig, ax, "1/φ", f"Q = ln(P/P_ref), ref {ref}", "q_lines", 6, ncol=2)
    return Claim("q-linear", "Overlapping histograms", "we always found a linear relation between "
                 "Q and the inverse volume fraction φ⁻¹", "Figs. 7b, 8b, section V",
                 f"{len(rows)} runs overlap the reference {ref}; curvatures " +
                 ", ".join(f"{r['quad']:.2g} ± {r['quad_err']:.2g}" for r in ok),
                 v.verdict, v.reason, _need(v, _n_med(st)), chart, **test_of(v))


def reference_overlap(st, budget):
    """section V: the g_p = 6 distribution overlaps every other one (it is the reference)"""
    ref = next((r for r in st.runs(NEG) if r["control"] == 6), None)
    quote = ("the distribution with g_p = 6 of the “negative g” protocol was chosen as the "
             "reference distribution, because it has sufficient overlap with all the other "
             "distributions")
    if ref is None:
        return Claim("reference-overlap", "Overlapping histograms", quote, "section V",
                     "no run at g_p = 6", UNRESOLVED, "the plan has no g_p = 6 run")
    rows = []
    others = [r for r in st.runs() if r["label"] != ref["label"]]
    ep_ref, es_ref, d_ref = phi_errors(st, ref)
    for r in others:
        # the regions where each density exceeds 5 % of its maximum (the paper's Q window)
        # meet when |Δφ̄| < √(2 ln 20)(σ₁ + σ₂); q = |Δφ̄| − that reach must be < 0
        reach = OVERLAP * (r["sigma"] + ref["sigma"])
        q = abs(r["phi_mean"] - ref["phi_mean"]) - reach
        ep, es, dof = phi_errors(st, r)
        e = math.hypot(math.hypot(ep, ep_ref), OVERLAP * math.hypot(es, es_ref))
        # any run apart makes the claim disagree: Bonferroni over the runs; |Δφ̄| is a modulus
        dof = None if dof is None or d_ref is None else min(dof, d_ref)
        rows.append((r["label"], q / reach + 1, below_bound(q, e, 0.0, ideal=-reach, dof=dof,
                                                           family=len(others), folded=True),
                     r["n_used"]))
    vs = {x[2].verdict for x in rows}
    v = DISAGREES if DISAGREES in vs else (AGREES if vs == {AGREES} else UNRESOLVED)
    if not rows:
        v, why, weak = UNRESOLVED, "no other run", None
    else:
        weak = max(rows, key=lambda x: x[1])
        apart = [x[0] for x in rows if x[2].verdict == DISAGREES]
        why = (f"{sum(x[2].verdict == AGREES for x in rows)} of {len(rows)} runs overlap g_p = 6 "
               f"with power ≥ 0.8; {len(apart)} lie apart at 1 % (Bonferroni over the runs)"
               + (f" ({', '.join(apart)})" if apart else "")
               + f"; farthest: {weak[0]}: {weak[2].reason}")
    fig, ax = _fig()
    for r in st.runs():
        ax.errorbar([r["phi_mean"]], [r["control"] if r["protocol"] == NEG else -r["control"]],
                    xerr=[OVERLAP * r["sigma"]], fmt="s" if r["protocol"] == NEG else "D", capsize=3,
                    color="k" if r["label"] == ref["label"] else None, label=r["label"])
    chart = _finish(st, fig, ax, "φ̄ ± σ_φ√(2 ln 20) (where each density exceeds 5 % of its maximum)",
                    "g_p (negative g) / −f in Hz (rotating g)", "reference_overlap", 6, ncol=2)
    return Claim("reference-overlap", "Overlapping histograms", quote, "section V, Figs. 7b, 8b",
                 "|Δφ̄| / (√(2 ln 20)(σ + σ_ref)), overlap below 1: "
                 + "; ".join(f"{l} {x:.2f}" for l, x, _, _ in rows), v, why,
                 _need(weak[2], weak[3]) if weak and v == UNRESOLVED else "", chart,
                 {"largest_separation": max((x[1] for x in rows), default=float("nan"))},
                 null="the two distributions coincide", alternative="the 5 %-of-maximum windows "
                 "just touch (the paper's overlap criterion)",
                 power=f"{min(x[2].power for x in rows):.2f}" if rows else "",
                 power_at=(lambda k: min(x[2].power_at(k) for x in rows)) if rows else None)


def constant_test(d, alt, inv):
    """χ² of d about its best constant (generalised least squares, inverse covariance inv), its
    degrees of freedom, and the noncentrality of alt about its own best constant"""
    one = np.ones(len(d))

    def chi(v):
        v = np.asarray(v, float)
        r = v - (one @ inv @ v) / (one @ inv @ one)
        return float(r @ inv @ r)
    return chi(d), len(d) - 1, chi(alt)


def two_refs_verdict(d, alt, inv, how):
    """the two-references rule: β̂(r1) − β̂(r2) of every common run is one constant; alt the
    differences the Gaussian pairs of App. A would give"""
    chi2, dof, lam = constant_test(d, alt, inv)

    def at(k):
        return chi2_power(lam * k, dof)
    return decide(chi2_sf(chi2, dof), at(1.0), "β̂ from the two references differ by a constant",
                  f"Gaussian pairs with the measured φ̄, σ_φ (App. A, A3–A4; noncentrality "
                  f"{lam:.3g})", f"χ² = {chi2:.3g} for {dof} degrees of freedom around a "
                  f"constant offset ({how})", float("nan"), power_at=at)


def two_references(st, budget):
    """Fig. 7c: β̂ from two references differ by a constant"""
    off = st.info.get("reference_offset", {})
    chi2, dof = off.get("chi2"), off.get("dof", 0)
    r1, r2 = st.info.get("reference"), st.info.get("reference2")
    by = {(r["reference"], r["label"]): r for r in st.beta if r.get("valid") == 1}
    common = [lab for (ref, lab) in by if ref == r1 and (r2, lab) in by]
    v_g = st.quadron.get("v_g", st.info.get("v_g"))
    rows = {r["label"]: r for r in st.summary}
    if len(common) < 2 or not v_g or r1 not in rows or r2 not in rows:
        v = Verdict(UNRESOLVED, "fewer than 2 runs overlap both references")
        p = float("nan")
    else:
        # the Gaussian pair of App. A: β̂ from (A3) are not additive, so their difference between
        # the references varies from run to run (A4's contradiction)
        d = np.array([by[(r1, lab)]["dbeta"] - by[(r2, lab)]["dbeta"] for lab in common])
        alt = np.array([gauss_dbeta(rows[lab]["phi_mean"], rows[lab]["sigma"],
                                    rows[r1]["phi_mean"], rows[r1]["sigma"], v_g)
                        - gauss_dbeta(rows[lab]["phi_mean"], rows[lab]["sigma"],
                                      rows[r2]["phi_mean"], rows[r2]["sigma"], v_g)
                        for lab in common])
        n1 = [f"direct:{r1}:{lab}" for lab in common]
        n2 = [f"direct:{r2}:{lab}" for lab in common]
        c = st.beta_cov(n1 + n2)
        inv, why = (None, "no beta_cov.csv") if c is None else cov_inverse(
            c[:len(common), :len(common)] + c[len(common):, len(common):]
            - c[:len(common), len(common):] - c[len(common):, :len(common)], st.replicas)
        if inv is not None:
            v = two_refs_verdict(d, alt, inv, f"with the bootstrap covariance of the {2 * len(common)} "
                                 f"β̂, {st.replicas} replicas; {why} eigenvalues floored")
        else:
            e2 = np.array([by[(r1, lab)]["dbeta_err"] ** 2 + by[(r2, lab)]["dbeta_err"] ** 2
                           for lab in common])
            v = without_covariance(two_refs_verdict(d, alt, np.diag(1 / e2), "errors independent"),
                                   f"β̂ of a run against the two references ({why})")
        p = chi2_sf(*constant_test(d, alt, inv if inv is not None else np.diag(1 / e2))[:2])
    fig, ax = _fig()
    for ref, mk in ((r1, "s"), (r2, "o")):
        rr = [r for r in st.beta if r.get("reference") == ref and r.get("valid") == 1]
        shift = off.get("dbeta", 0.0) if ref == r2 else 0.0
        ax.errorbar(column(rr, "phi_mean"), column(rr, "dbeta") + (shift or 0.0),
                    yerr=1.96 * column(rr, "dbeta_err"), fmt=mk, capsize=2,
                    label=f"reference {ref}" + (" (+ offset)" if shift else ""))
    chart = _finish(st, fig, ax, "φ̄", "β̂ (1/m²)", "two_references", 8)
    return Claim("two-references", "Overlapping histograms", "the values determined for β using "
                 "different samples as reference distribution may only differ by an additive "
                 "constant", "Fig. 7c, eq. (39)",
                 (f"offset {off.get('dbeta'):.4g} ± {1.96 * off.get('err'):.2g} 1/m², χ² {chi2:.3g} "
                  f"for {dof} d.o.f. (errors independent)" if math.isfinite(p) else
                  "no second reference with ≥ 2 common runs"), v.verdict, v.reason,
                 _need(v, _n_med(st)), chart, {"p": p}, **test_of(v))


def quadron_claims(st, budget):
    """Figs. 9–11: one β(φ̄) curve, the ideal-quadron fit and what it predicts"""
    out = []
    name, fit = _fit(st)
    lim = limits(st)
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
    v_g = st.quadron.get("v_g", st.info.get("v_g"))
    use_joint = name == "joint"
    groups, bh_of = curve_points(st, name, a, b0)
    gm, ge, names = [], [], []
    for g, vals in groups.items():
        w = np.array([1 / x[1] ** 2 for x in vals])
        gm.append(float(np.sum(w * np.array([x[0] for x in vals])) / w.sum()))
        ge.append(float(1 / math.sqrt(w.sum())))
        names.append(g)
    # the residuals are from a fit to these very runs: the test refits N z̄/V_g and β₀
    # (linearized about the fit) with and without an offset per protocol and branch
    labs = [g for g, vals in groups.items() for _ in vals]
    y = np.array([x[0] for vals in groups.values() for x in vals])
    e = np.array([x[1] for vals in groups.values() for x in vals])
    jac = np.array([x[3] for vals in groups.values() for x in vals])
    # the residuals' covariance: φ̄'s own error beside the β̂ covariance carried through the curve
    # (φ_quadron moves by dp per unit of β̂), where the analysis shipped it
    pts = [x for vals in groups.values() for x in vals]
    inv, why = residual_cov_inverse(st, name, pts)
    how = (f"with the bootstrap covariance of the β̂ ({st.replicas} replicas; {why} eigenvalues "
           "floored)" if inv is not None else None)
    v = Verdict(UNRESOLVED, "fewer than 2 protocols or branches with β̂, or too few runs to "
                "refit the curve with an offset per group")
    if len(names) >= 2 and len(y) > len(names) + 2:
        alts = {g: np.array([x[2] if gi == g else 0.0 for gi, vals in groups.items() for x in vals])
                for g in names}
        v = one_curve_test(labs, y, e, jac, alts, inv)
        if inv is None:
            v = without_covariance(v, f"β̂ of different runs ({why})")
    decoy = _decoy_note(st, bh_of, v_g)
    # the chart draws the estimate the quadron-a claim reports, over every run's φ̄
    est = quadron_estimate(st)
    fig, ax = _fig()
    rows = [r for r in st.summary if r["label"] in bh_of]
    for proto, mk in ((NEG, "s"), (ROT, "D")):
        sel = [r for r in rows if r["protocol"] == proto]
        if sel:
            ax.errorbar(column(sel, "phi_mean"), [bh_of[r["label"]][0] + est["beta0"] for r in sel],
                        xerr=1.96 * column(sel, "phi_err"),
                        yerr=[1.96 * bh_of[r["label"]][1] for r in sel], fmt=mk, capsize=2,
                        label=f"gransim {proto} (95 %)")
    if rows:
        phi = column(rows, "phi_mean")
        x = np.linspace(max(phi.min() - 0.002, lim[0] + 1e-4),
                        min(phi.max() + 0.002, lim[1] - 1e-4), 80)
        ax.plot(x, [quadron_beta(v, est["a"], lim) for v in x], "k-", lw=1,
                label=f"ideal quadron (26), N z̄/V_g = {est['a']:.0f} ± "
                      f"{1.96 * est['a_err']:.0f} m⁻²")
    chart = _finish(st, fig, ax, "φ̄", "β = β̂ + β₀ (1/m²)", "beta_phi", 8)
    out.append(Claim("one-curve", "Edwards statistics", "All the data, whether obtained from the "
                     "branch left of the minimum or the branch right of the minimum in the φ(g_p) "
                     "curve … or else from the “rotating g” protocol, [fall on one curve]",
                     "Fig. 9, section V", "mean residual φ̄ − φ_quadron(β̂ + β₀) per group: " +
                     "; ".join(f"{n} {m:+.4f} ± {1.96 * e:.4f}" for n, m, e in zip(names, gm, ge)),
                     v.verdict, v.reason + f" (β̂ from the {'joint multiple-histogram' if use_joint else 'direct'} "
                     f"fit{'; ' + how if how else ''})" + decoy, _need(v, _n_med(st)), chart,
                     **test_of(v)))

    # N z̄/V_g of the fit over every run; with the β̂ covariance, one generalised least-squares
    # step from the fit gives the estimate and its error
    a_fit, a_err, b0 = est["a"], est["a_err"], est["beta0"]
    c = compare_value(a_fit, a_err, A_PAPER, alternative=A_PREC * A_PAPER, fmt="{:.4g}")
    c.alternative = f"a {100 * A_PREC:.0f} % difference (the paper's precision of its fit, section V)"
    if not est["gls"]:
        c = without_covariance(c, f"β̂ of different runs the fit is made from ({est['how']})")
    else:
        c.reason += f" ({est['how']})"
    out.append(Claim("quadron-a", "Edwards statistics", "we find as fitting value N z̄/V_g = "
                     "556.51 m⁻²", "Fig. 9, eq. (26), section V",
                     f"N z̄/V_g = {a_fit:.4g} ± {1.96 * a_err:.3g} m⁻², "
                     f"β₀ = {b0:.4g} 1/m² ({name} fit, φ_rlp = {lim[0]}, φ_rcp = {lim[1]})",
                     c.verdict, c.reason, _need(c, _n_med(st)), chart,
                     {"a": a_fit, "a_err": a_err, "beta0": b0}, **test_of(c)))

    # fits to one protocol alone
    fits = st.quadron.get("fits", {})
    fn, fr = fits.get(NEG, {}), fits.get(ROT, {})
    quote = ("When we used only the data obtained by one of the protocols … The relative "
             "deviation of the obtained fitting parameters is smaller than 2%")
    if fn.get("converged") and fr.get("converged"):
        rel = abs(fn["a"] - fr["a"]) / a
        err = math.hypot(fn.get("a_err", 0), fr.get("a_err", 0)) / a
        bb = below_bound(rel, err, 0.02)
        out.append(Claim("protocol-fits", "Edwards statistics", quote, "section V",
                         f"N z̄/V_g: negative g {fn['a']:.4g} ± {1.96 * fn.get('a_err', 0):.3g}, "
                         f"rotating g {fr['a']:.4g} ± {1.96 * fr.get('a_err', 0):.3g} m⁻²",
                         bb.verdict, bb.reason, _need(bb, _n_med(st)), **test_of(bb)))
    else:
        out.append(Claim("protocol-fits", "Edwards statistics", quote, "section V",
                         "a protocol's own fit did not converge", UNRESOLVED,
                         "each protocol needs ≥ 3 runs with β̂ for its own fit", nxt))

    out.append(_lnz(st, budget))
    out.append(_sigma_phi(st, budget))
    return out


def one_curve_test(groups, resid, err, jac, alts, inv=None):
    """the one-curve rule: residuals from a fit (nuisance Jacobian jac, n × 2) refitted with and
    without an offset per group; alts {group: the residuals if that group lay on a curve 2 % off},
    the worst-seen group being the alternative; inv the residuals' inverse covariance (None:
    independent errors err)"""
    lam, g = min((offset_test(jac, groups, resid, err, alts[g], inv)[2], g) for g in alts)
    dchi, dof, _ = offset_test(jac, groups, resid, err, inv=inv)

    def at(k):
        return chi2_power(lam * k, dof)
    return decide(chi2_sf(dchi, dof), at(1.0), "one curve: no offset between protocols and "
                  "branches", f"one group ({g}) on a curve with N z̄/V_g {100 * A_PREC:.0f} % off "
                  f"(the paper's precision of its fit; noncentrality {lam:.3g})",
                  f"offsets per group lower χ² by {dchi:.3g} for {dof} degrees of freedom (the "
                  "fit's N z̄/V_g and β₀ refitted)", float("nan"), power_at=at)


def _decoy_note(st, bh_of, v_g):
    """how far the β̂ lie from the Gaussian pairs' chain (A3 through the runs in order of φ̄)"""
    ref = st.info.get("reference")
    rows = sorted((r for r in st.summary if r["label"] in bh_of or r["label"] == ref),
                  key=lambda r: r["phi_mean"])
    if not v_g or not any(r["label"] == ref for r in rows) or len(rows) < 3:
        return ""
    i0 = next(i for i, r in enumerate(rows) if r["label"] == ref)
    chain = {ref: 0.0}
    for step in (1, -1):
        i = i0
        while 0 <= i + step < len(rows):
            a, b = rows[i], rows[i + step]
            chain[b["label"]] = chain[a["label"]] + gauss_dbeta(b["phi_mean"], b["sigma"],
                                                                a["phi_mean"], a["sigma"], v_g)
            i += step
    z = [abs(bh_of[k][0] - chain[k]) / bh_of[k][1] for k in bh_of
         if k != ref and bh_of[k][1] > 0]
    if not z:
        return ""
    return (f". The β̂ lie within {max(z):.1f}σ of the chain that Gaussian pairs with the "
            "measured φ̄ and σ_φ alone give (App. A, A3): Gaussian decoys with these moments "
            "would fall on the same curve")


def conditional_err(eb, el, cov, slope):
    """the error of Δln Z − slope·Δβ when Δβ, Δln Z have errors eb, el and covariance cov:
    el²(1 − ρ²) + eb²(slope − cov/eb²)², written so that ρ → ±1 does not cancel"""
    if not eb > 0:
        return el
    vb = eb * eb
    return math.sqrt(max(el * el - cov * cov / vb, 0.0) + vb * (slope - cov / vb) ** 2)


def _lnz(st, budget):
    """Fig. 10: Δln Z against the fit's prediction, with the Δβ–Δln Z covariance"""
    ref = st.info.get("reference")
    rr = _ref_row(st, ref)
    v_g = st.quadron.get("v_g", st.info.get("v_g"))
    rows = [r for r in st.primary_beta() if r.get("valid") == 1 and r["label"] != ref
            and math.isfinite(r.get("dlnz_quadron", float("nan")))]
    res, err, alt = [], [], []
    for r in rows:
        # Δln Z and Δβ come from one line fit: the prediction moves with Δβ by
        # −V_g/φ̄_quadron, so the residual's error is the conditional one
        res.append(r["dlnz"] - r["dlnz_quadron"])
        err.append(conditional_err(r["dbeta_err"], r["dlnz_err"], r.get("cov", 0.0),
                                   -v_g / r["phi_quadron"]))
        alt.append(gauss_dlnz_excess(r["phi_mean"], r["sigma"], rr["phi_mean"], rr["sigma"])
                   if rr else float("nan"))
    v, _ = chi2_consistent(res, err, "runs' Δln Z − quadron residuals",
                           alternative=alt if rr else None,
                           alt_text="the intercepts of Gaussian pairs with the measured φ̄ and "
                           "σ_φ (App. A, A6): " + ", ".join(f"{x:+.2g}" for x in alt))
    fig, ax = _fig()
    ax.errorbar(column(rows, "phi_mean"), res, yerr=1.96 * np.array(err), fmt="o", capsize=2,
                label="gransim Δln Z − fit (conditional 95 % error)")
    ax.axhline(0, color="k", lw=1, label="ideal quadron fit")
    ch = _finish(st, fig, ax, "φ̄", "Δln Z − Δln Z_quadron(β̂)", "lnz", 8)
    # the analysis predicts Δln Z from its fit to these same direct β̂ (not the joint one)
    fa = st.quadron.get("fits", {}).get("all", {})
    of = (f" (the fit to the direct β̂: N z̄/V_g = {fa['a']:.0f} ± {1.96 * fa['a_err']:.0f} m⁻², "
          f"β₀ = {fa['beta0']:.4g} 1/m²)" if fa.get("converged") else "")
    return Claim("lnz", "Edwards statistics", "the numerically determined values and the ideal "
                 "quadron solution fit very well, independently of the protocol and of the branch",
                 "Fig. 10, eq. (21)", f"Δln Z − fit{of}: " + "; ".join(
                     f"{r['label']} {x:+.3g} ± {1.96 * e:.2g}" for r, x, e in zip(rows, res, err)),
                 v.verdict, v.reason + " (errors conditional on Δβ through their covariance)",
                 _need(v, _n_med(st)), ch, **test_of(v))


def _sigma_phi(st, budget):
    """Fig. 11: σ_φ(φ̄) of every run, both protocols and branches, against eq. (17) on the fit"""
    from .tapping_protocols import sigma_phi  # the σ_φ claims share their test there
    return sigma_phi(st, budget)

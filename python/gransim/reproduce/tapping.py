"""The tapping paper's claims (Becker & Kassner 2015) against a `gransim reproduce tapping` run.
Each function reads the analysis, decides a verdict with verdicts.py and draws its chart."""
import math

import numpy as np

from .report import Claim, test_of
from . import described
from .batch import batch_err, f_power, normal_score
from .tapping_data import (NEG, ROT, Study, _fig, _finish, _pm, _save, column, phi_errors,
                          sigma_err, steady_window)
from .tapping_protocols import protocol_claims
from .tapping_edwards import (quadron_claims, q_linear, reference_overlap, sigma_peak_effect,
                             two_references)
from .verdicts import (AGREES, DISAGREES, P_KEEP, P_REJECT, UNRESOLVED, Verdict, below_bound,
                      chi2_consistent, compare_value, decide, extremum, f_sf, mean_err, offset_test,
                      t_sf2, z_of)

# the paper's resolution of φ: "the typical magnitude of the observed static volume fraction
# fluctuations" is 100 × 10⁻⁵ (section III); the smallest transient or feature its figures show
PHI_RES = 1e-3
PHI_RES_SRC = "10⁻³, the typical static fluctuation section III states"
NO_TAPS = "the per-tap series (taps.csv) of the runs are not in this folder"


def _need(v, n, unit="taps"):
    return v.need(n, unit) if v.verdict == UNRESOLVED else ""


def transient(st, budget):
    """Fig. 4: the steady state within ~10 taps"""
    rows, cuts = [], []
    fig, ax = _fig()
    for r in st.runs():
        lab = r["label"]
        if math.isfinite(r.get("discard", float("nan"))):
            cuts.append(f"{lab} {int(r['discard'])}" + ("" if r.get("steady", 1) else " (no steady part)"))
        d, e, dof = steady_window(lab, st, 6, 10)
        if not math.isfinite(d):
            continue
        # the χ² below takes each run's t as the normal deviate of equal tail probability
        rows.append((lab, normal_score(d / e, dof) * e, e))
        taps = st.taps(lab)
        tap, phi = column(taps, "tap"), column(taps, "phi") - float(np.mean(st.used(lab, "phi")))
        line, = ax.plot(tap, phi, lw=0.8, label=lab)
        at = tap == st.cut(lab)  # where the analysis' steady part begins
        ax.plot(tap[at], phi[at], "o", ms=4, color=line.get_color())
    ax.axvline(10, color="k", ls="--", lw=1, label="paper: steady after < 10 taps")
    ax.plot([], [], "o", ms=4, color="gray", label="each run's cut (MSER-5, at least 10)")
    chart = _finish(st, fig, ax, "tap", "φ − steady φ̄", "transient", 6, ncol=2)
    if not rows:
        v = Verdict(UNRESOLVED, "no run has taps 6–10 and a steady part"
                    + ("" if any(st.taps(r["label"]) for r in st.runs()) else f": {NO_TAPS}"))
    else:
        # every run's taps 6–10 against its steady mean; the alternative: a transient of the
        # paper's resolution left at taps 6–10 in every run
        v, _ = chi2_consistent([x[1] for x in rows], [x[2] for x in rows],
                               "runs' (mean of taps 6–10 − steady φ̄)",
                               alternative=[PHI_RES] * len(rows),
                               alt_text=f"a transient of {PHI_RES:g} left at taps 6–10 "
                               f"({PHI_RES_SRC})")
    return Claim("steady-state", "Transient", "The mean volume fraction reaches a steady state "
                 "value very quickly (after approximately < 10 taps)", "Fig. 4, section IV",
                 "(mean of taps 6–10 − steady φ̄)/σ per run: "
                 + "; ".join(f"{lab} {d / e:+.1f}" for lab, d, e in rows)
                 + (". Taps dropped as the transient (the larger of 10 and the MSER-5 cut): "
                    + "; ".join(cuts) if cuts else ""),
                 v.verdict, v.reason, _need(v, len(rows), "runs (each gives one taps 6–10 mean)"),
                 chart, {"max_z": max((abs(d / e) for _, d, e in rows), default=float("nan"))},
                 **test_of(v))


def _curve(st, protocol, key):
    rows = st.runs(protocol)
    x = column(rows, "control")
    if key == "phi":
        return x, column(rows, "phi_mean"), column(rows, "phi_err")
    return x, column(rows, "sigma"), np.array([sigma_err(r) for r in rows])


def _n_med(rows):
    n = column(rows, "n_used")
    return float(np.nanmedian(n)) if len(n) else float("nan")


def neg_minimum(st, budget):
    """Fig. 5a: φ̄(g_p) falls to a minimum near g_p ≈ 20 and rises beyond it"""
    x, y, e = _curve(st, NEG, "phi")
    v, at = extremum(x, y, e, "min", expect_at=20.0, effect=PHI_RES, effect_source=PHI_RES_SRC)
    fig, ax = _fig()
    ax.errorbar(x, y, yerr=1.96 * e, fmt="o-", capsize=3, label="gransim (95 % CI, τ-corrected)")
    ax.axvspan(16, 24, color="tab:orange", alpha=0.2, label="paper: minimum near g_p ≈ 20")
    chart = _finish(st, fig, ax, "g_p", "φ̄", "neg_phi_mean", 8)
    meas = "; ".join(f"g_p={xi:g}: {_pm(yi, ei)}" for xi, yi, ei in zip(x, y, e))
    return Claim("neg-minimum", "Negative g", "the volume fraction decreases with increasing pulse "
                 "strength until it reaches a local minimum around g_p = 20. Afterwards, the "
                 "volume fraction increases with the pulse strength.", "Fig. 5a, section IV",
                 meas, v.verdict, v.reason, _need(v, _n_med(st.runs(NEG)), "taps per value"),
                 chart, {"minimum_at": at if at is not None else float("nan")}, **test_of(v)), at


def neg_sigma_maximum(st, budget, at):
    """Fig. 5b: σ_φ has a local maximum where φ̄ is minimal"""
    x, y, e = _curve(st, NEG, "sigma")
    where = at if at is not None else 20.0
    effect, src = sigma_peak_effect(st)
    v, mx = extremum(x, y, e, "max", expect_at=where, effect=effect, effect_source=src)
    fig, ax = _fig()
    ax.errorbar(x, y, yerr=1.96 * e, fmt="s-", capsize=3, color="tab:red", label="gransim σ_φ")
    ax.axvline(where, color="k", ls="--", lw=1,
               label=f"minimum of φ̄ ({'measured' if at is not None else 'paper'}: {where:g})")
    chart = _finish(st, fig, ax, "g_p", "σ_φ", "neg_sigma", 8)
    meas = "; ".join(f"g_p={xi:g}: {_pm(yi, ei, 5)}" for xi, yi, ei in zip(x, y, e))
    return Claim("neg-sigma-maximum", "Negative g", "At the same value of g_p, where the volume "
                 "fraction is minimal, the volume fraction fluctuations have a local maximum",
                 "Fig. 5b, section IV", meas, v.verdict, v.reason,
                 _need(v, _n_med(st.runs(NEG)), "taps per value"), chart,
                 {"maximum_at": mx if mx is not None else float("nan")}, **test_of(v))


def _plateau(y, e, i, j):
    """z of the difference between two points of a curve that the source says is level there"""
    return (y[i] - y[j]) / math.hypot(e[i], e[j])


def _welch(e1, d1, e2, d2):
    """Welch–Satterthwaite degrees of freedom of a difference of two estimates (None: normal)"""
    if d1 is None or d2 is None:
        return None
    return (e1 ** 2 + e2 ** 2) ** 2 / (e1 ** 4 / d1 + e2 ** 4 / d2)


def rot_crossover(st, budget):
    """Fig. 6a: φ̄(f) crosses over from ≈ 0.814 to ≈ 0.821"""
    x, y, e = _curve(st, ROT, "phi")
    errs = [phi_errors(st, r) for r in st.runs(ROT)]
    e, dofs = np.array([t[0] for t in errs], float), [t[2] for t in errs]
    n = _n_med(st.runs(ROT))
    fig, ax = _fig()
    ax.errorbar(x, y, yerr=1.96 * e, fmt="D-", capsize=3, label="gransim")
    ax.axhline(0.814, color="tab:orange", ls=":", label="paper: ≈ 0.814 (low f)")
    ax.axhline(0.821, color="tab:green", ls=":", label="paper: ≈ 0.821 (high f)")
    chart = _finish(st, fig, ax, "f (Hz)", "φ̄", "rot_phi_mean", 8)
    meas = "; ".join(f"f={xi:g} Hz: {_pm(yi, ei)}" for xi, yi, ei in zip(x, y, e))
    quote = ("With increasing frequency the mean volume fraction shows a crossover from "
             "φ̄ ≃ 0.814 to φ̄ ≃ 0.821")
    levels = "φ̄ ≃ 0.814 at low frequency, φ̄ ≃ 0.821 at high frequency"
    if len(x) < 2:  # a study still running, before its rotating-g runs
        return [Claim(cid, "Rotating g", q, "Fig. 6a, section IV", meas or "no runs yet",
                      UNRESOLVED, "fewer than 2 rotating-g runs", f"the {budget} budget once "
                      "its rotating-g runs are done", chart) for cid, q in
                (("rot-crossover", quote), ("rot-levels", levels))]
    o = np.argsort(x)
    x, y, e, dofs = x[o], y[o], e[o], [dofs[i] for i in o]
    rnd = "both levels printed to three decimals, ± 0.0005 each"
    step = compare_value(float(y[-1] - y[0]), float(math.hypot(e[-1], e[0])), 0.007,
                         tolerance=0.001, alternative=0.007, precision=rnd,
                         dof=_welch(e[0], dofs[0], e[-1], dofs[-1]))
    step.alternative = "no crossover (a flat curve, 0.007 below the source's step)"
    rising = len(x) >= 3 and _plateau(y, e, -1, -2) > z_of(P_KEEP / 2)
    why = f"change from the lowest to the highest f: {step.reason}"
    need = _need(step, n, "taps per value")
    if rising and step.verdict != AGREES and y[-1] - y[0] < 0.007:
        # a curve still rising where the scan ends gives a lower bound on the step
        step.verdict = UNRESOLVED
        why += (f"; φ̄ still rises by {_plateau(y, e, -1, -2):.1f}σ from f = {x[-2]:g} Hz, so the "
                "scan's step is a lower bound on the crossover")
        need = f"frequencies beyond {x[-1]:g} Hz, up to the plateau"
    cross = Claim("rot-crossover", "Rotating g", quote, "Fig. 6a, section IV", meas, step.verdict,
                  why, need, chart, **test_of(step))
    parts, vs, pws, need, ats = [], [], [], [], []
    for k, j, src, side in ((0, 1, 0.814, "low f"), (-1, -2, 0.821, "high f")):
        # either level off makes the claim disagree: Bonferroni over the two
        c = compare_value(float(y[k]), float(e[k]), src, tolerance=0.0005, alternative=0.001,
                          precision="printed to three decimals", dof=dofs[k], family=2)
        z = _plateau(y, e, k, j) if len(x) >= 3 else 0.0
        if abs(z) > z_of(P_KEEP / 2):
            # the source's level is a plateau (section IV): a curve still moving at the end of
            # the scan has not reached it, so the run is not under the claim's conditions
            vs.append(UNRESOLVED)
            parts.append(f"{side} (f = {x[k]:g} Hz): {c.reason}; but φ̄ still changes by "
                         f"{abs(z):.1f}σ from f = {x[j]:g} Hz: the scan does not reach the "
                         "plateau the level is claimed for")
            need.append(f"frequencies beyond {x[k]:g} Hz" if k else f"frequencies below {x[k]:g} Hz")
        else:
            vs.append(c.verdict)
            parts.append(f"{side} (f = {x[k]:g} Hz): {c.reason}")
            if c.verdict == UNRESOLVED:
                need.append(c.need(n, "taps per value"))
        pws.append(c.power)
        ats.append(c.power_at)
    v = DISAGREES if DISAGREES in vs else (AGREES if set(vs) == {AGREES} else UNRESOLVED)
    lev = Claim("rot-levels", "Rotating g", levels, "Fig. 6a, section IV",
                f"f={x[0]:g} Hz: {_pm(y[0], e[0])}; f={x[-1]:g} Hz: {_pm(y[-1], e[-1])}",
                v, "; ".join(parts), "; ".join(x for x in need if x) if v == UNRESOLVED else "",
                chart, {"phi_low_f": y[0], "phi_high_f": y[-1]},
                null="each level = the source's ± 0.0005",
                alternative="a level 0.001 away (the neighbouring printed value)",
                power=f"{min(pws):.2f}", power_at=lambda k: min(f(k) for f in ats))
    return [cross, lev]


def _sigma_ratio(p, pl, pr):
    """the columns' mean σ_φ over the whole square's, √2 for independent columns"""
    return 0.5 * (np.std(pl, ddof=1) + np.std(pr, ddof=1)) / np.std(p, ddof=1)


def halves(st, budget):
    """section IV: the two columns of the test square against the whole"""
    mean_rows, ratio_rows = [], []
    for r in st.runs():
        lab = r["label"]
        pl, pr, p = (st.used(lab, k) for k in ("phi_left", "phi_right", "phi"))
        if len(p) < 10 or not np.all(np.isfinite(pl)):
            continue
        rel = (pl - p) / p
        m, e, dof = batch_err(rel)
        mean_rows.append((lab, abs(m), e, len(p), dof))
        ratio, re, rdof = batch_err([p, pl, pr], _sigma_ratio)
        ratio_rows.append((lab, ratio, re, len(p), rdof))
    out = []
    for rows, cid, bound, quote, unit in (
            (mean_rows, "halves-mean", 1e-4, "The relative difference of mean volume fraction "
             "(after 2500 taps) between the columns and the entire test volume was always smaller "
             "than 0.01 %", "relative difference"),
            (ratio_rows, "halves-sigma", 0.01, "the deviation of the volume fraction fluctuation "
             "ratio from √2 was always lower than 1 %", "|ratio/√2 − 1|")):
        if not rows:
            out.append(Claim(cid, "Test volume", quote, "section IV", "no run with φ_left, φ_right",
                             UNRESOLVED, NO_TAPS if not any(st.taps(r["label"]) for r in st.runs())
                             else "no run with φ_left, φ_right"))
            continue
        verdicts = []
        for lab, val, err, n, dof in rows:
            q = abs(val / math.sqrt(2) - 1) if cid == "halves-sigma" else val
            qe = err / math.sqrt(2) if cid == "halves-sigma" else err
            # any run above the bound makes the claim disagree: Bonferroni over the runs keeps
            # the claim's level at 1 %; the statistic is a modulus, so its test is two-sided
            verdicts.append((below_bound(q, qe, bound, dof=dof, family=len(rows), folded=True),
                             lab, q, qe, n))
        vs = {t[0].verdict for t in verdicts}
        v = DISAGREES if DISAGREES in vs else (AGREES if vs == {AGREES} else UNRESOLVED)
        worst = max(verdicts, key=lambda t: t[2] + 2 * t[3])
        weakest = min(verdicts, key=lambda t: t[0].power)
        n_min = min(t[4] for t in verdicts)
        # the runs that decide a disagreement, which need not be the one with the largest value
        above = [f"{t[1]}: {t[2]:.3g} ± {t[3]:.2g}" for t in verdicts if t[0].verdict == DISAGREES]
        cond = (f"; the source's bound is on 2500-tap means, these runs have {n_min:.0f}+ taps"
                if n_min < 2500 else "")
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
                         f"below the bound with power ≥ 0.8, "
                         f"{len(above)} above it at 1 % (Bonferroni over the runs)"
                         + (f" ({'; '.join(above)})" if above else "")
                         + f"; worst: {worst[0].reason}{cond}",
                         _need(weakest[0], weakest[4], "taps per value"),
                         chart, {"worst": worst[2], "worst_err": worst[3]},
                         null=f"{unit} = 0 in every run", alternative=f"{unit} at the bound "
                         f"{bound:g} (the source's)", power=f"{weakest[0].power:.2f}",
                         power_at=weakest[0].power_at))
    return out


def normality(st, budget):
    """section V: the χ² test rejects normality for every sample"""
    rows = st.runs()
    rej = [r for r in rows if r.get("normal") == 0]
    n_min = min((r["n_used"] for r in rows), default=0)
    # the source names no size for the departure from normality, so no power can be stated:
    # a rejection in every run agrees (each is a 5 % test); a kept normality contradicts the
    # claim only in series as long as the paper's (2500 taps), for which it is made
    if rows and len(rej) == len(rows):
        v, why = AGREES, f"normality rejected at 5 % in all {len(rows)} runs"
    elif n_min >= 2500:
        v, why = DISAGREES, (f"normality kept in {len(rows) - len(rej)} of {len(rows)} runs of "
                             "≥ 2500 taps, the paper's length")
    else:
        v, why = UNRESOLVED, (f"rejected in {len(rej)} of {len(rows)} runs; the claim is made "
                              f"for the paper's 2500-tap series, these have {n_min:.0f}+ taps "
                              "(its own test runs of ≈ 100 taps did not reject either [57])")
    return Claim("normality", "Distributions", "The null hypothesis that the data is normally "
                 "distributed was rejected for all samples", "section V and note [57]",
                 "χ² test p-values: " + ", ".join(f"{r['label']} {r['chi2_p']:.2g}" for r in rows),
                 v, why + "; the source gives no size for the non-normality, so no power",
                 "" if v != UNRESOLVED else "2500 taps per value (the paper's series)",
                 null="each run's φ is normally distributed",
                 alternative="none sized by the source (non-Gaussian tails)")


def _groups(st):
    """protocol and branch of each run: negative g left and right of the φ̄ minimum, rotating g"""
    neg = st.runs(NEG)
    at = neg[int(np.argmin(column(neg, "phi_mean")))]["control"] if len(neg) >= 3 else None
    out = {}
    for r in st.runs():
        out[r["label"]] = r["protocol"] if r["protocol"] == ROT or at is None else (
            f"{NEG} g_p ≤ {at:g}" if r["control"] <= at else f"{NEG} g_p > {at:g}")
    return out


def stress_offsets(x, groups, comps, offset):
    """Δχ² that an offset per protocol or branch gains over one smooth (quadratic) S(φ̄), its
    degrees of freedom, and the noncentrality of offsets of `offset` between the groups, summed
    over the components. comps: {name: (y, err)}; returns (Δχ², dof, λ)"""
    x = np.asarray(x, float)
    names = list(dict.fromkeys(groups))
    base = np.vstack([np.ones_like(x), x - x.mean(), (x - x.mean()) ** 2]).T
    alt = np.array([offset * names.index(g) for g in groups])  # each group a further offset away
    d_chi = lam = 0.0
    dof = 0
    for y, e in comps.values():
        d, k, l_ = offset_test(base, groups, y, e, alt)
        d_chi, lam, dof = d_chi + d, lam + l_, dof + k
    return d_chi, dof, lam


def stress_test(x, groups, comps, offset=0.01):
    """the stress claim's test: comps {name: (means, errors, batch dof)} of each run. The
    errors are estimated from batches, so Δχ²/dof is taken as Fisher's F against the harmonic
    mean ν of the runs' batch degrees of freedom (Satterthwaite's for a sum of equally weighted
    estimated variances; a χ² test would find offsets in pure noise several times more often than
    its level); the power at longer runs keeps that ν"""
    groups = list(groups)
    names = sorted(set(groups))
    dchi, dof, lam = stress_offsets(x, groups, {k: c[:2] for k, c in comps.items()}, offset)
    dofs = np.concatenate([np.asarray(c[2], float) for c in comps.values()])
    nu = float(len(dofs) / np.sum(1.0 / dofs))

    def at(k):
        return f_power(lam * k, dof, nu)
    return decide(f_sf(dchi / dof, dof, nu), at(1.0),
                  "one smooth (quadratic) S(φ̄) for every protocol and branch",
                  f"offsets of {offset:g} N·m between protocols and branches (the source's "
                  "'order of 0.01 Nm')",
                  f"offsets per group ({', '.join(names)}) lower χ² by {dchi:.3g} for {dof} "
                  f"degrees of freedom, F = {dchi / dof:.3g} against {nu:.3g} degrees of freedom "
                  "(the runs' batch errors)", float("nan"), feature=True, power_at=at)


def stress(st, budget):
    """Fig. 12: the stress tensor is not a unique function of φ̄"""
    pts = []
    grp = _groups(st)
    for r in st.runs():
        lab = r["label"]
        comp = {k: batch_err(st.used(lab, k)) for k in ("S_xx", "S_yy", "S_xy")}
        if all(math.isfinite(v[0]) and v[1] > 0 for v in comp.values()):
            pts.append((r["protocol"], r["phi_mean"], comp, grp[lab]))
    fig, ax = _fig()
    for k, col in (("S_xx", "tab:blue"), ("S_yy", "tab:red"), ("S_xy", "tab:green")):
        for proto, mk in ((NEG, "D"), (ROT, "x")):
            sel = [p for p in pts if p[0] == proto]
            if sel:
                ax.errorbar([p[1] for p in sel], [p[2][k][0] for p in sel],
                            yerr=[1.96 * p[2][k][1] for p in sel], fmt=mk, color=col,
                            label=f"{k} {proto}")
    chart = _finish(st, fig, ax, "φ̄", "S_ab (N·m)", "stress", 6, ncol=2)
    names = sorted({p[3] for p in pts})
    if len(pts) < len(names) + 4 or len(names) < 2:
        v = Verdict(UNRESOLVED, (NO_TAPS if not pts and not any(st.taps(r["label"]) for r in st.runs())
                                 else "too few runs for a smooth curve and an offset per group"))
    else:
        comps = {k: tuple(np.array([p[2][k][j] for p in pts]) for j in range(3))
                 for k in ("S_xx", "S_yy", "S_xy")}
        v = stress_test([p[1] for p in pts], [p[3] for p in pts], comps)
    return Claim("stress", "Stress", "The stress tensor is obviously not a unique function of the "
                 "volume fraction … deviations … on the order of 0.01 Nm", "Fig. 12, eq. (41)",
                 f"{len(pts)} runs in {len(names)} protocols and branches", v.verdict, v.reason,
                 _need(v, _n_med(st.runs()), "taps per value"), chart, **test_of(v))


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
        m, e = mean_err(d[k > st.cut(r["label"])])
        rows.append((r["label"], m - d[0], e))
        ax.plot(k, d - d[0], lw=0.8, label=r["label"])
    ax.axhline(0, color="k", lw=1, label="paper: no segregation")
    chart = _finish(st, fig, ax, "tap", "Δ(z̄_big − z̄_small) since tap 0 (mm)", "segregation", 6, ncol=2)
    # the distance wanders slowly (over tens of taps), so one run's error from its own taps is
    # too small; the runs are independent: their drifts' mean and scatter decide (Student t)
    drifts = np.array([x[1] for x in rows])
    null, alt = "mean drift = 0", "none: the source gives no size of segregation"
    if len(drifts) < 3:
        v = Verdict(UNRESOLVED, NO_TAPS if not rows else "fewer than 3 runs", null, alt)
    else:
        m = float(drifts.mean())
        se = float(drifts.std(ddof=1) / math.sqrt(len(drifts)))
        p = t_sf2(abs(m) / se, len(drifts) - 1) if se > 0 else 1.0
        why = (f"mean drift over {len(drifts)} runs {m:+.2f} ± {se:.2f} mm (scatter of the runs), "
               f"t = {m / se:+.2f} for {len(drifts) - 1} d.o.f., p = {p:.3g}; the source states "
               "no size of segregation that would count, so the drift's error alone decides and "
               "no power can be stated")
        v = Verdict(DISAGREES if p < P_REJECT else UNRESOLVED, why, null, alt)
    return Claim("segregation", "Segregation", "no segregation (big and small grains stay mixed "
                 "from tap to tap)", "section IV (segregation check)",
                 "drift of z̄_big − z̄_small after the transient, mm: " +
                 "; ".join(f"{l} {d:+.2f} ± {1.96 * e:.2f}" for l, d, e in rows),
                 v.verdict, v.reason, "" if v.verdict != UNRESOLVED else
                 "a size of segregation from the source, or runs precise enough to reject drift",
                 chart, **test_of(v))


PAPER_PILE = "the paper's pile is 1184 bidisperse decagons"


def pile_of(st):
    """the pile the study's runs tapped, from their scene.toml (None without one)"""
    return described.pile(described.scenes(sorted(set(st.run_dir.values()))))


def pile_text(st):
    p = pile_of(st)
    if p is None:
        return "their scene.toml files are not in this folder, so the pile is not described"
    same = p["grains"] == [1184]
    return (p["text"] + " (from the runs' scene.toml" +
            ("" if same else f"; not the paper's pile: {PAPER_PILE}, docs/tapping.md") + ")")


def departure_facts(folder):
    """the runs' own pile for the departures table"""
    return pile_of(Study(folder))


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
    out += protocol_claims(st, budget)
    out += [stress(st, budget), segregation(st, budget)]
    runs = st.runs()
    taps = ", ".join(f"{r['label']} {r['n_used']:.0f}" for r in runs)
    rule = (f"the larger of {st.discard} and the cut of the marginal standard error rule "
            "(MSER-5)") if st.info.get("discard_auto") else f"the first {st.discard}"
    notes = [f"Taps used per run after its transient ({rule}): {taps}.",
             "Errors are standard errors with the integrated autocorrelation time (n_eff = n/2τ); "
             "intervals are 95 %. β̂ of runs that do not overlap the reference come from the joint "
             "multiple-histogram fit (analysis/beta_multi.csv, beside the direct and chained "
             "estimates).",
             "Each claim's test names its null, the alternative the paper names or shows, and "
             "its power against that alternative at this length (the power column): a claim "
             "agrees only with power ≥ 0.80 at the 5 % level, disagrees only at the 1 % level "
             "(a missing feature: only where it would have been found with power ≥ 0.99), and "
             "is otherwise not resolved with the length it would need. For the Edwards claims "
             "the alternative is App. A's Gaussian pair with the measured φ̄ and σ_φ, or a "
             "protocol 2 % off the fit (the paper's stated precision). Tolerances are only "
             "those the paper states, quoted where used. docs/reproduction/power.md tabulates "
             "each claim's power by series length."]
    intro = ("The tapping paper (V. Becker and K. Kassner, Protocol-independent granular "
             "temperature supported by numerical simulations, 2015) against gransim's runs: "
             + pile_text(st) + ". The pulse is read as g_p·g for t1 (docs/physics.md). Every "
             "verdict is computed from the data.")
    return "Reproduction of the tapping study", intro, out, notes

"""Claims of the tapping paper that span its two protocols: σ_φ(f) (Fig. 6b), σ_φ as one
function of φ̄ over protocols and branches (eq. (17) with the ideal quadron (26), Fig. 11: the
claim sigma-phi of the Edwards statistics),
β̂ from references of either protocol (Fig. 8c), and the time-step check (section IV)."""
import math

import numpy as np

from .report import Claim, test_of
from .tapping_data import NEXT, ROT, _fig, _finish, column, sigma_err
from .tapping_edwards import _n_med, _need, gauss_dbeta
from .tapping_quadron import A_PREC, limits, quadron_estimate
from .verdicts import UNRESOLVED, Verdict, chi2_sf, focused_test, tau_int


def _langevin(x):
    return 1 / math.tanh(x) - 1 / x if abs(x) > 1e-4 else x / 3 - x ** 3 / 45


def _langevin_deriv(x):
    return 1 / x ** 2 - 1 / math.sinh(x) ** 2 if abs(x) > 1e-3 else 1 / 3 - x ** 2 / 15


def _langevin_inverse(y):
    lo, hi = -1e3, 1e3
    for _ in range(64):  # 2e3 / 2⁶⁴: below a double's resolution of x
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _langevin(mid) < y else (lo, mid)
    return 0.5 * (lo + hi)


def sigma_of_phi(phi, a, v_g, rlp=0.81, rcp=0.855):
    """σ_φ at mean φ̄ from (17) with the ideal quadron (26): σ² = φ̄²/V_g·∂φ̄/∂β at the β where
    φ̄(β) = φ̄; nan outside the quadron's range of φ̄"""
    d = 1 / rlp - 1 / rcp
    y = (1 / rlp - 1 / phi) / d
    if not (-1 < y < 1 and a > 0 and v_g > 0):
        return float("nan")
    x = _langevin_inverse(y)
    return math.sqrt(phi ** 2 / v_g * phi ** 2 * d ** 2 * _langevin_deriv(x) / a)


def _groups(st):
    from .tapping_quadron import _groups_of  # protocol and branch, as one-curve and stress
    return _groups_of(st)


def sigma_verdict(phi, sigma, err, groups, a, a_err, v_g, lim=(0.81, 0.855), phi_err=None):
    """σ_φ of runs against (17) with the ideal quadron (26) of N z̄/V_g = a. The fit's error
    a_err moves every prediction together (a common covariance); φ̄'s error moves each along
    the curve. The alternative is the paper's precision of its fit, a group (protocol or
    branch) on the curve of N z̄/V_g 2 % off, the group the runs see worst; the focused part
    is a relative offset of σ_φ per group. Returns (Verdict, predictions, residuals / error)
    with nan predictions for runs outside the quadron's φ range (left out)."""
    phi, sigma, err = (np.asarray(v, float) for v in (phi, sigma, err))
    phi_err = np.zeros_like(phi) if phi_err is None else np.asarray(phi_err, float)
    pred = np.array([sigma_of_phi(p, a, v_g, *lim) for p in phi])
    ok = np.isfinite(pred) & np.isfinite(sigma) & np.isfinite(err) & (err > 0)
    null = "σ_φ of every run lies on (17) with the quadron fit"
    if ok.sum() < 2:
        return (Verdict(UNRESOLVED, "fewer than 2 runs with σ_φ inside the quadron's φ range",
                        null, "", float("nan")), pred, np.full(len(phi), np.nan))
    idx = np.flatnonzero(ok)
    h = 1e-6 * phi[idx]
    slope = np.array([(sigma_of_phi(p + d, a, v_g, *lim) - sigma_of_phi(p - d, a, v_g, *lim))
                      / (2 * d) if pe else 0.0 for p, d, pe in zip(phi[idx], h, phi_err[idx])])
    e = np.hypot(err[idx], slope * phi_err[idx])
    res = sigma[idx] - pred[idx]
    cov = np.diag(e ** 2)
    if a_err and math.isfinite(a_err):
        jac = -pred[idx] / (2 * a)  # σ ∝ a^(-1/2)
        cov = cov + np.outer(jac, jac) * a_err ** 2
    inv = np.linalg.inv(cov)
    g = [groups[i] for i in idx]
    names = list(dict.fromkeys(g))
    u = np.array([[pred[i] if gi == n else 0.0 for n in names] for i, gi in zip(idx, g)])
    fisher = u.T @ inv @ u

    def along(v):
        w = u.T @ inv @ v
        return float(w @ np.linalg.solve(fisher, w))
    off = np.array([sigma_of_phi(p, a * (1 + A_PREC), v_g, *lim) for p in phi[idx]]) - pred[idx]
    lam, worst = min((along(np.where(np.array(g) == n, off, 0.0)), n) for n in names)
    v = focused_test(float(res @ inv @ res), len(idx), along(res), len(names), lam, null,
                     f"one group ({worst}) on (17) with N z̄/V_g {100 * A_PREC:.0f} % off (the "
                     "paper's precision of its fit, section V)",
                     f"{len(idx)} runs in {len(names)} group{'s' if len(names) > 1 else ''} "
                     f"against σ_φ(φ̄) of (17) with N z̄/V_g = {a:.0f} ± {a_err:.0f} m⁻² "
                     "(its error correlating the runs)")
    z = np.full(len(phi), np.nan)
    z[idx] = res / e
    return v, pred, z


def _sigma_runs(st, rows):
    """the quadron fit and the σ_φ verdict of `rows`; None without a converged fit"""
    est = quadron_estimate(st)  # the N z̄/V_g the quadron-a claim reports
    if est is None:
        return None
    name = est["name"]
    v_g = st.quadron.get("v_g", st.info.get("v_g", float("nan")))
    lim = limits(st)
    groups = _groups(st)
    a, a_err = est["a"], est["a_err"]
    v, pred, z = sigma_verdict(column(rows, "phi_mean"), column(rows, "sigma"),
                               [sigma_err(r) for r in rows], [groups[r["label"]] for r in rows],
                               a, a_err, v_g, lim, column(rows, "phi_err"))
    return {"v": v, "pred": pred, "z": z, "a": a, "a_err": a_err, "fit": name, "lim": lim,
            "v_g": v_g, "groups": groups}


def _sigma_chart(st, rows, t, name):
    fig, ax = _fig()
    for g in dict.fromkeys(t["groups"][r["label"]] for r in rows):
        sel = [r for r in rows if t["groups"][r["label"]] == g]
        ax.errorbar(column(sel, "phi_mean"), column(sel, "sigma"),
                    yerr=[1.96 * sigma_err(r) for r in sel], fmt="o", capsize=2, label=g)
    phi = column(rows, "phi_mean")
    x = np.linspace(phi.min() - 0.002, phi.max() + 0.002, 60)
    ax.plot(x, [sigma_of_phi(v, t["a"], t["v_g"], *t["lim"]) for v in x], "k-",
            label=f"(17) with the quadron fit, N z̄/V_g = {t['a']:.0f} m⁻²")
    return _finish(st, fig, ax, "φ̄", "σ_φ", name, 7)


def _residuals(rows, t):
    by = {}
    for r, z in zip(rows, t["z"]):
        if math.isfinite(z):
            by.setdefault(t["groups"][r["label"]], []).append(z)
    return "; ".join(f"{g} " + ", ".join(f"{z:+.1f}" for z in zs) for g, zs in by.items())


def rot_sigma(st, budget):
    """Fig. 6b read with Fig. 11: σ_φ(f) of rotating g on the curve of the negative-g runs"""
    rows = st.runs(ROT)
    meas = "; ".join(f"f={r['control']:g} Hz: {r['sigma']:.5f} [{r['sigma_lo_tau']:.5f}, "
                     f"{r['sigma_hi_tau']:.5f}]" for r in rows) or "no rotating-g run"
    t = _sigma_runs(st, rows) if len(rows) >= 2 else None
    if t is None:
        v = Verdict(UNRESOLVED, "no ideal-quadron fit, or fewer than 2 rotating-g runs with σ_φ")
        chart = ""
    else:
        v = t["v"]
        meas += "; residuals from (17) in σ: " + _residuals(rows, t)
        chart = _sigma_chart(st, rows, t, "rot_sigma")
    return Claim("rot-sigma", "Across the protocols", "(b) shows the standard deviation of the "
                 "volume fraction fluctuations [against the rotation frequency]; Fig. 11 puts "
                 "these points on the ideal-quadron σ_φ(φ̄) (blue points)", "Fig. 6b, Fig. 11",
                 "σ_φ with τ-corrected 95 % intervals: " + meas, v.verdict,
                 v.reason + ". Fig. 6b gives no value of its own: the rotating-g runs are tested "
                 "alone against the curve (sigma-phi tests every run)",
                 _need(v, _n_med(st)) if v.verdict == UNRESOLVED else "", chart, **test_of(v))


def sigma_phi(st, budget):
    """eq. (17), Fig. 11: σ_φ of every run, both protocols and both branches, on one curve"""
    rows = st.runs()
    t = _sigma_runs(st, rows)
    quote = ("Using (26) in (17), we get the relationship between the mean volume fraction and "
             "its fluctuations … The data is in good agreement with the theory for both protocols")
    if t is None:
        return Claim("sigma-phi", "Edwards statistics", quote, "Fig. 11, eqs. (17), (26)",
                     "no fit", UNRESOLVED, "the ideal-quadron fit did not converge (too few runs "
                     "with β̂)", f"the {NEXT[budget]} budget")
    v = t["v"]
    return Claim("sigma-phi", "Edwards statistics", quote, "Fig. 11, eqs. (17), (26)",
                 f"{int(np.isfinite(t['z']).sum())} runs against σ_φ(φ̄) of (17) with N z̄/V_g = "
                 f"{t['a']:.0f} ± {1.96 * t['a_err']:.0f} m⁻²; residuals in σ: "
                 + _residuals(rows, t),
                 v.verdict, v.reason + ". Gaussian pairs satisfy eq. (17) by construction (App. A, "
                 "A5): only a protocol or branch dependence can fail it",
                 _need(v, _n_med(st)) if v.verdict == UNRESOLVED else "",
                 _sigma_chart(st, rows, t, "sigma-phi"), **test_of(v))


def histogram_dbeta(phi_x, phi_r, v_g):
    """Δβ = β_x − β_ref and its error from the overlap of two runs' distributions of φ (eqs.
    (19), (39)): ln(P_x/P_ref) = −Δβ·V_g/φ + const. Given the pooled taps, whether a tap is run
    x's is then a logistic function of V_g/φ with slope −Δβ: the overlapping-histogram fit
    with bins of one tap each, which no choice of bins or of a count threshold can bias. Its
    variance is multiplied by the larger 2τ_int of the two runs; nan when fewer than 3 taps of
    each run lie where the two overlap"""
    ux, ur = v_g / np.asarray(phi_x, float), v_g / np.asarray(phi_r, float)
    lo, hi = max(ux.min(), ur.min()), min(ux.max(), ur.max())
    inside = lambda v: int(((v >= lo) & (v <= hi)).sum())  # noqa: E731
    if len(ux) < 8 or len(ur) < 8 or not hi > lo or min(inside(ux), inside(ur)) < 3:
        return float("nan"), float("nan")
    u = np.concatenate([ux, ur])
    y = np.concatenate([np.ones(len(ux)), np.zeros(len(ur))])
    u0, us = u.mean(), u.std()
    X = np.column_stack([np.ones_like(u), (u - u0) / us])  # centred and scaled
    w = np.array([math.log(len(ux) / len(ur)), 0.0])
    for _ in range(100):  # Newton–Raphson on the likelihood
        p = 1 / (1 + np.exp(-np.clip(X @ w, -500, 500)))
        info = X.T @ (X * (p * (1 - p))[:, None])
        step = np.linalg.solve(info, X.T @ (y - p))
        w += step
        if np.max(np.abs(step)) < 1e-10:
            break
    else:
        return float("nan"), float("nan")  # (nearly) separated: no overlap to fit
    p = 1 / (1 + np.exp(-(X @ w)))
    cov = np.linalg.inv(X.T @ (X * (p * (1 - p))[:, None]))
    infl = 2 * max(tau_int(phi_x), tau_int(phi_r))
    return float(-w[1] / us), float(math.sqrt(cov[1, 1] * infl) / us)


def _references(st):
    """the references of Fig. 8c: the negative-g reference and the rotating-g runs nearest
    0.5 Hz and 1.25 Hz"""
    refs = [st.info.get("reference")] if st.info.get("reference") else []
    rot = st.runs(ROT)
    for f in (0.5, 1.25):
        if rot:
            r = min(rot, key=lambda q: abs(q["control"] - f))["label"]
            if r not in refs:
                refs.append(r)
    return refs


def offsets_test(betas, base, others):
    """χ² of β̂_base(x) − β̂_other(x) around one constant per other reference; the two estimates
    share run x, so treating them as independent makes the test conservative"""
    chi2, dof, rows = 0.0, 0, []
    for o in others:
        d = [(x, b - betas[o][x][0], math.hypot(e, betas[o][x][1]))
             for x, (b, e) in betas[base].items()
             if x in betas[o] and math.isfinite(b) and math.isfinite(betas[o][x][0])
             and math.hypot(e, betas[o][x][1]) > 0]
        if len(d) < 3:
            continue
        w = np.array([1 / q[2] ** 2 for q in d])
        v = np.array([q[1] for q in d])
        c = float((w * v).sum() / w.sum())
        chi2 += float((w * (v - c) ** 2).sum())
        dof += len(d) - 1
        rows.append((o, c, 1 / math.sqrt(w.sum()), len(d), d))
    return chi2, dof, rows


def stacked(rows):
    """offsets_test's differences as one vector: their (other reference, run) keys, the values
    and the design matrix of one constant per other reference"""
    keys, v, design = [], [], []
    for k, (o, _, _, _, d) in enumerate(rows):
        for x, diff, _ in d:
            keys.append((o, x))
            v.append(diff)
            design.append([1.0 if j == k else 0.0 for j in range(len(rows))])
    return keys, np.array(v), np.array(design).reshape(len(v), len(rows))


def dbeta_covariance(used, base, keys, v_g, reps=200, seed=0):
    """the covariance of the differences β̂_base(x) − β̂_o(x) for (o, x) in keys, by one
    moving-block bootstrap over every run's taps at once (blocks of 2τ_int taps, at least 1):
    the differences share run x, and those of one other reference share it too, so their errors
    are correlated. None when a quarter of the replicas lose a difference (too little overlap)"""
    rng = np.random.default_rng(seed)
    runs = sorted({base} | {o for o, _ in keys} | {x for _, x in keys})
    series = {r: np.asarray(used[r], float) for r in runs}
    block = {r: max(1, int(round(2 * tau_int(series[r])))) for r in runs}

    def resample(x, b):
        n = len(x)
        starts = rng.integers(0, max(1, n - b + 1), -(-n // b))
        return np.concatenate([x[s:s + b] for s in starts])[:n]

    def beta(x, ref, res):
        return 0.0 if x == ref else histogram_dbeta(res[x], res[ref], v_g)[0]
    out = []
    for _ in range(reps):
        res = {r: resample(series[r], block[r]) for r in runs}
        row = [beta(x, base, res) - beta(x, o, res) for o, x in keys]
        if all(math.isfinite(q) for q in row):
            out.append(row)
    if len(out) < 0.75 * reps or len(out) <= len(keys):
        return None
    return np.cov(np.array(out), rowvar=False).reshape(len(keys), len(keys))


def offsets_gls(rows, alts, cov=None):
    """generalised least squares on offsets_test's rows: one constant per other reference
    fitted to the stacked differences with weights cov⁻¹ (cov in stacked() order; None: each
    difference's own error, independent). Returns (χ² of the residuals, its degrees of
    freedom, the residuals' product with the centred alternative alts {other: {run: value}},
    that alternative's own χ²)"""
    keys, v, design = stacked(rows)
    if cov is None:
        w = np.diag([1 / q[2] ** 2 for _, _, _, _, d in rows for q in d])
    else:
        w = np.linalg.inv(cov)

    def residual(y):  # y less its generalised least-squares constants
        return y - design @ np.linalg.solve(design.T @ w @ design, design.T @ w @ y)
    r = residual(v)
    a = residual(np.array([alts[o][x] for o, x in keys]))
    return float(r @ w @ r), len(v) - len(rows), float(r @ w @ a), float(a @ w @ a)


def references_verdict(rows, alts, cov=None):
    """the verdict on offsets_test's rows: rows' differences β̂_base − β̂_other should be one
    constant per other reference; alts {other: {run: the difference Gaussian pairs with the
    measured φ̄ and σ_φ give}} (App. A, A3: their β̂ are not additive, A4), centred like the
    data (offsets_gls); the focused part is the data's projection on that pattern"""
    null = "β̂ with references of either protocol differ by one constant per reference"
    alt = "Gaussian pairs with the measured φ̄ and σ_φ (App. A, A3–A4: β̂ not additive)"
    if sum(len(d) for _, _, _, _, d in rows) - len(rows) < 2:
        return Verdict(UNRESOLVED, "fewer than 3 runs overlap both a negative-g and a "
                       "rotating-g reference", null, alt, float("nan"))
    full, dof, dot, lam = offsets_gls(rows, alts, cov)
    how = ("bootstrap covariance of the differences, over blocks of taps of every run at once"
           if cov is not None else "each difference's own error (their correlation not known)")
    return focused_test(full, dof, dot * dot / lam if lam > 0 else 0.0, 1, lam, null, alt,
                        "offsets per reference pair (β̂ from the overlap of the runs' taps: a "
                        "logistic fit of which run a tap belongs to against V_g/φ, overlapping "
                        f"histograms of one tap a bin; {how})")


def _references_chart(st, refs, betas, rows):
    fig, ax = _fig()
    phi = {r["label"]: r["phi_mean"] for r in st.runs()}
    for ref, mk in zip(refs, "sDo"):
        shift = next((c for o, c, _, _, _ in rows if o == ref), 0.0)
        pts = sorted((phi[x], b + shift, e) for x, (b, e) in betas.get(ref, {}).items())
        if pts:
            ax.errorbar([p[0] for p in pts], [p[1] for p in pts],
                        yerr=[1.96 * p[2] for p in pts], fmt=mk, capsize=2,
                        label=f"reference {ref}" + (" (+ offset)" if shift else ""))
    return _finish(st, fig, ax, "φ̄", "β̂ − β_ref (1/m²)", "cross_references", 7)


def cross_references(st, budget):
    """Fig. 8c: β̂ with references of either protocol differ by a constant"""
    refs = _references(st)
    v_g = st.info.get("v_g", st.quadron.get("v_g", float("nan")))
    used = {r["label"]: st.used(r["label"], "phi") for r in st.runs()}
    row = {r["label"]: r for r in st.runs()}
    betas = {}
    for ref in refs:
        betas[ref] = {ref: (0.0, 0.0)}
        for lab, phi in used.items():
            if lab != ref and len(phi) and len(used.get(ref, [])):
                b, e = histogram_dbeta(phi, used[ref], v_g)
                if math.isfinite(b):
                    betas[ref][lab] = (b, e)
    chi2, dof, rows = (offsets_test(betas, refs[0], refs[1:]) if len(refs) >= 2
                       else (0.0, 0, []))
    cov = dbeta_covariance(used, refs[0], stacked(rows)[0], v_g) if dof >= 2 else None

    def gauss(x, r):
        return gauss_dbeta(row[x]["phi_mean"], row[x]["sigma"], row[r]["phi_mean"],
                           row[r]["sigma"], v_g)
    alts = {o: {x: gauss(x, refs[0]) - gauss(x, o) for x, _, _ in d} for o, _, _, _, d in rows}
    v = references_verdict(rows, alts, cov)
    if dof >= 2:
        chi2, dof = offsets_gls(rows, alts, cov)[:2]
    taps = any(len(u) for u in used.values())
    if dof < 2:
        v.reason += (" (references " + (", ".join(refs) or "none") + "; "
                     + ("their taps do not overlap enough" if taps else
                        "no per-tap series in this folder") + ")")
    chart = _references_chart(st, refs, betas, rows) if any(len(b) > 1 for b in betas.values()) \
        else ""  # no β̂ to draw without the runs' taps
    meas = "; ".join(f"{refs[0]} − {o}: offset {c:.4g} ± {1.96 * e:.2g} 1/m² over {n} runs"
                     for o, c, e, n, _ in rows) or f"references {', '.join(refs) or 'none'}"
    resolve = ""
    if v.verdict == UNRESOLVED:
        resolve = (_need(v, _n_med(st)) if math.isfinite(v.power) else
                   f"the {NEXT[budget]} budget" if taps else
                   "the per-tap series of the runs (shipped series/ or the run folders)")
    return Claim("cross-references", "Across the protocols", "It even applies if we use "
                 "samples from the “negative g” protocol as reference distribution, in "
                 "agreement with the fact that the predictions of Edwards’ theory should be "
                 "protocol independent", "Fig. 8c, section V", meas, v.verdict, v.reason, resolve,
                 chart, {"p": chi2_sf(chi2, dof) if dof else float("nan")}, **test_of(v))


def protocol_claims(st, budget):
    """the claims of this module and the time-step check, in the report's order"""
    from .tapping_timestep import timestep
    return [rot_sigma(st, budget), cross_references(st, budget), timestep(st, budget)]

"""The thesis' 1D claims over ε and in time: ξ₂ over ε (Fig. 3.2), the collapse of ⟨v²⟩ onto one
curve of ε (Fig. 3.3), ξ_m at the near-elastic extreme (Fig. 3.4a) and the ring's temperature
settling (Figs. 2.7–2.8), against DIR/analysis/{ring,ring_eps,ring_n512} of `gransim reproduce
rfm`."""
import math

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from .rfm_conditions import THESIS, misses, plan_conditions  # noqa: E402
from .rfm_data import (Missing, _ax, _chart, _ci, _gate, _runs, pooled, seed_mean,  # noqa: E402
                       t_blocks)
from .rfm_ring import (_seeds, _two_sided, bonferroni, eps_values, exponents, fewer_dof,  # noqa: E402
                       moments)
from .verdicts import (UNRESOLVED, Verdict, chi2_consistent, chi2_sf, compare_value,  # noqa: E402
                       decide, phi, power_two_sided, t_sf2)

XI2, XI2_TOL, XI2_ALT = 0.53, 0.005, 0.01  # "≃ 0.53" to two decimals; c_xi2's alternative
PLATEAU = 0.5                              # "in the range 0 ≤ ε ≤ 0.5"
MEAN_FIELD = 2 / 3


def _ring_points(d, sw, other="ring"):
    """every ε of sweep sw and of `other` (the ring at ε = 0.1), each with its moments() table and
    its runs; the gate's verdict on `other` for claim cid is applied by the caller"""
    pts, runs = {}, []
    for s in dict.fromkeys((sw, other)):
        try:
            rs = _runs(d, s)  # first: its message names the folder, not this machine's path
            c = moments(d, s)
        except Missing:
            if s == sw:
                raise
            continue
        runs += rs
        for e in eps_values(c):
            pts.setdefault(e, (s, c))
    return pts, runs


def _others(d, cid, pts, sw, v):
    """v, or not resolved when a sweep other than sw that gave points misses the thesis'
    conditions; when sw misses them too, the report's gate says so and the others' misses
    are added to the reason"""
    conds = plan_conditions(d)
    if not conds:
        return v
    out = []
    for s in dict.fromkeys(x for x, _ in pts.values()):
        m = (misses(cid, conds[s]) if s in conds else
             [f"the plan states no conditions for sweep {s}"]) if s != sw else []
        if m:
            out.append(f"sweep {s} has " + "; ".join(m))
    if not out:
        return v
    what = "; ".join(out)
    if sw not in conds or misses(cid, conds[sw]):
        return Verdict(v.verdict, f"{v.reason} (and {what})", v.null, v.alternative, v.power,
                       v.scale_, v.power_at)
    face = v.reason if v.verdict == UNRESOLVED else f"{v.verdict}, {v.reason}"
    return Verdict(UNRESOLVED, f"not at the thesis' conditions ({THESIS[cid]['source']}): {what}; "
                   f"at face value: {face}", v.null, v.alternative, v.power, math.nan)


def xi2_fits(tables):
    """ξ₂ at every ε of {ε: moments() table}: {ε: dict(use, inside, xi, err, a, chi2, dof,
    tdof)}, dof the fit's and tdof the t test's on ξ₂ (None when the errors are known)"""
    fit = {}
    for e, c in sorted(tables.items()):
        use, inside, x = exponents(c, e, [2])
        fit[e] = dict(c=c, use=use, inside=inside, xi=x[2][0], err=x[2][1], a=x[2][2],
                      chi2=x[2][3], dof=x[2][4], tdof=x[2][5])
    return fit


def _xi2_by_eps(d, sw):
    pts, runs = _ring_points(d, sw)
    fit = xi2_fits({e: c for e, (_, c) in pts.items()})
    for e, f in fit.items():
        f["sweep"] = pts[e][0]
    return fit, runs, pts


def xi2eps_test(fit):
    """the plateau ξ₂ = 0.53 ± 0.005 at ε ≤ 0.5 and the bound ξ₂ ≤ 2/3 above, over the ε of
    xi2_fits whose sizes are the thesis'"""
    low = {e: f for e, f in fit.items() if e <= PLATEAU + 1e-9 and f["inside"]}
    if not low:
        raise Missing(f"no ε ≤ {PLATEAU:g} with two sizes N ≥ 398")
    parts, rows = [], []
    for e, f in fit.items():
        if not f["inside"]:
            continue
        x, s, dof = f["xi"], f["err"], f.get("tdof")
        if e in low:  # the plateau: 0.53 to two decimals, a failure at 0.01 (as for xi2)
            parts.append((_two_sided(x, s, XI2, XI2_TOL, dof=dof), lambda a, s=s, dof=dof: (
                lambda k: power_two_sided(XI2_ALT, s / math.sqrt(k), XI2_TOL, alpha=a, dof=dof))))
        else:  # eq. 3.9's bound ξ₂ < 2/3: one-sided, the thesis sizes no gap
            z = (x - MEAN_FIELD) / s
            one = 1.0 - phi(z) if dof is None else (
                0.5 * t_sf2(z, dof) if z > 0 else 1.0 - 0.5 * t_sf2(-z, dof))
            parts.append((one, None))
        rows.append(f"ε = {e:g}: {_ci(x, s, dof)}")
    return bonferroni(parts, f"ξ₂ = {XI2} ± {XI2_TOL} for ε ≤ {PLATEAU:g} and ξ₂ ≤ 2/3 above",
                      f"ξ₂ {XI2_ALT} off 0.53 at one ε ≤ {PLATEAU:g} (0.53 printed to two "
                      "decimals)", "ξ₂ " + "; ".join(rows) + f" (95 %; plateau points against "
                      f"0.53 ± {XI2_TOL}, the others against the bound 2/3, one-sided)")


def c_xi2eps(d, sw="ring_eps"):
    fit, runs, pts = _xi2_by_eps(d, sw)
    v = xi2eps_test(fit)
    out = [f"{e:g}" for e, f in fit.items() if not f["inside"]]
    if out:
        v.reason += f"; ε = {', '.join(out)} left out: fewer than two sizes N ≥ 398"
    v = _others(d, "xi2-eps", pts, sw, _gate(v, runs))

    def draw(ax):
        e = np.array(list(fit))
        ax.errorbar(e, [f["xi"] for f in fit.values()], [1.96 * f["err"] for f in fit.values()],
                    fmt="o", capsize=3, label="gransim ξ₂, 95 %")
        ax.axhline(0.528, color="C3", ls="--", label="thesis Fig. 3.2: 0.528 (ε ≤ 0.5)")
        ax.axhline(MEAN_FIELD, color="k", ls=":", label="mean field 2/3 (the bound of T.3.9)")
        ax.axvspan(0, PLATEAU, color="C3", alpha=0.08, label="the thesis' plateau 0 ≤ ε ≤ 0.5")
        ax.set_xlim(0, 1)
        _ax(ax, "ξ₂ of ⟨v²⟩ ∝ N^−ξ₂ over ε, N ≥ 398 (thesis Fig. 3.2)", "ε", "ξ₂")
    return dict(measured="ξ₂ at " + "; ".join(
                f"ε = {e:g}: {_ci(f['xi'], f['err'], f['tdof'])} over N = "
                + ", ".join(f"{n:g}" for n in f["use"]) for e, f in fit.items()) + " (95 %)",
                verdict=v, chart=_chart(d, "xi2-eps", draw),
                values={f"xi2_eps{e:g}": f["xi"] for e, f in fit.items()})


def collapse_test(fit):
    """⟨v²⟩ about N^−ξ₂(ε) at every ε of xi2_fits with the thesis' sizes and a residual: the
    verdict and the ε used"""
    use = {e: f for e, f in fit.items() if f["inside"] and f["dof"] > 0}
    if not use:
        raise Missing("no ε with three sizes N ≥ 398: a collapse needs a residual")
    chi2, dof = sum(f["chi2"] for f in use.values()), sum(f["dof"] for f in use.values())
    p = chi2_sf(chi2, dof)
    return decide(p, math.nan, "⟨v²⟩·N^ξ₂(ε) is one value at each ε for every N (T.3.8: one "
                  "curve of 1 − ε²)", "none sized by the thesis",
                  f"χ² = {chi2:.3g} for {dof} degrees of freedom of ⟨v²⟩ about N^−ξ₂(ε) at ε = "
                  + ", ".join(f"{e:g} (χ² {f['chi2']:.2g}/{f['dof']})" for e, f in use.items()),
                  math.nan), use, chi2, dof, p


def c_collapse(d, sw="ring_eps"):
    fit, runs, pts = _xi2_by_eps(d, sw)
    v, use, chi2, dof, p = collapse_test(fit)
    v = _others(d, "collapse", pts, sw, _gate(v, runs))

    def draw(ax):
        ns = sorted({n for f in use.values() for n in f["use"]})
        for k, n in enumerate(ns):
            xs, ys, es = [], [], []
            for e, f in use.items():
                c = f["c"]
                r = ((c["dimension"] == 1) & (np.abs(c["eps_n"] - e) < 1e-9) & (c["N"] == n)
                     & (c["m"] == 2))
                if r.any():
                    xs.append(1 - e * e)
                    ys.append(c["v_moment"][r][0] * n ** f["xi"])
                    es.append(1.96 * c["v_err"][r][0] * n ** f["xi"])
            ax.errorbar(xs, ys, es, fmt="osd^<>v"[k % 7], capsize=2, label=f"N = {n:g}")
        _ax(ax, "⟨v²⟩ compensated by the fitted N^ξ₂(ε); thesis Fig. 3.3: one curve\n"
            "for N = 631…10⁴ (its ξ₂ ≃ 0.528 for ε ≤ 0.5)", "1 − ε²", "⟨v²⟩ N^ξ₂ (m²/s²)",
            True, True)
    return dict(measured=f"χ² = {chi2:.3g} for {dof} (p = {p:.2g}) over ε = "
                + ", ".join(f"{e:g}" for e in use), verdict=v,
                chart=_chart(d, "collapse", draw), values=dict(chi2=chi2, dof=dof, p=p))


# Fig. 3.4(a), ε = 0.999: ⟨|v|⟩ ∝ N^−0.328 (lower line), ⟨|v|⁹⟩^(1/9) ∝ N^−0.309 (upper line)
ELASTIC, XI1_E, XI9_E = 0.999, 0.328, 0.309


def xim_elastic_test(c, e):
    """ξ₉/9 − ξ₁ of a moments() table at ε = e against Fig. 3.4(a): the verdict, the sizes and
    the fits of m = 1…9"""
    use, inside, xi = exponents(c, e, range(1, 10))
    y, s = xi[9][0] / 9 - xi[1][0], math.hypot(xi[1][1], xi[9][1] / 9)
    # Fig. 3.4a read to three decimals (± 0.0005 at each end); the alternative: no decrease
    v = compare_value(y, s, XI9_E - XI1_E, tolerance=0.001, alternative=XI1_E - XI9_E,
                      precision="0.328 and 0.309 read to three decimals", fmt="{:.3g}",
                      dof=fewer_dof(xi[1][5], xi[9][5]))
    v = Verdict(v.verdict, f"ξ₉/9 − ξ₁ at ε = {e:g}: " + v.reason, v.null,
                f"no decrease of ξ_m/m ({XI1_E - XI9_E:.3g} from the thesis' change)", v.power,
                v.scale_, v.power_at)
    if not inside:
        sizes = ", ".join(f"{n:g}" for n in use)
        face = "" if v.verdict == UNRESOLVED else f"at face value: {v.verdict}, "
        v = Verdict(UNRESOLVED, f"sizes N = {sizes} lie below the thesis' N ≥ 398; {face}{v.reason}",
                    v.null, v.alternative, v.power, v.scale)
    return v, use, xi


def c_xim_elastic(d, sw="ring_eps"):
    runs, c = _runs(d, sw), moments(d, sw)
    eps = eps_values(c)
    e = max(eps)
    v, use, xi = xim_elastic_test(c, e)
    sizes = ", ".join(f"{n:g}" for n in use)
    v = _gate(v, runs)
    others = {}
    for x in eps:
        try:
            others[x] = exponents(c, x, range(1, 10))[2]
        except Missing:
            pass
    try:  # the near-inelastic ring beside it, as in Fig. 3.5
        r = moments(d, "ring")
        others.update({x: exponents(r, x, range(1, 10))[2] for x in eps_values(r) if x not in others})
    except Missing:
        pass

    def draw(ax):
        m = np.arange(1, 10)
        for k, (x, f) in enumerate(sorted(others.items())):
            ax.errorbar(m + 0.04 * k, [f[j][0] / j for j in m], [1.96 * f[j][1] / j for j in m],
                        fmt="o-", ms=3, lw=0.7, capsize=2, label=f"gransim ε = {x:g}, 95 %")
        ax.plot([1, 9], [XI1_E, XI9_E], "C3s--", label="thesis Fig. 3.4a (ε = 0.999): 0.328 → 0.309")
        ax.plot([1, 9], [0.264, 0.228], "C3^:", label="thesis Fig. 3.4b (ε = 0.001): 0.264 → 0.228")
        ax.axhline(1 / 3, color="k", ls=":", label="mean field 1/3")
        _ax(ax, f"ξ_m/m over ε (thesis Fig. 3.5), N = {sizes}", "m", "ξ_m / m", fs=7)
    return dict(measured=f"at ε = {e:g}: ξ₁ = {_ci(*xi[1][:2], xi[1][5])}, ξ₉/9 = {_ci(xi[9][0] / 9, xi[9][1] / 9, xi[9][5])}"
                f" (95 %) over N = {sizes}; the thesis' extreme is ε = {ELASTIC:g}" + _seeds(c),
                verdict=v, chart=_chart(d, "xi-m-elastic", draw),
                values=dict(eps=e, xi1=xi[1][0], xi9_9=xi[9][0] / 9))


# ---- the temperature in time ------------------------------------------------------------------

BLOCK = 20.0  # Fig. 2.8's periods (s)


def _periods(t, T, n, end, length):
    """means of T over the whole periods of `length` from t[0], and their mid-times: T the means
    of blocks of n samples whose first sample is at t (exact when the periods are made of whole
    blocks), end the time of the last sample"""
    p = int(math.floor((end - t[0]) / length + 1e-6))
    k = np.floor((t - t[0]) / length + 1e-9).astype(int)
    ks = [j for j in range(p) if n[k == j].sum() > 1]
    return (np.array([(n[k == j] * T[k == j]).sum() / n[k == j].sum() for j in ks]),
            np.array([t[0] + (j + 0.5) * length for j in ks]))


def drift(groups):
    """the linear trend of each seed's period means (y, mid-times t), merged over the seeds by
    seed_mean (the larger of the runs' own errors and the seeds' scatter, which a slow wandering
    that the periods share cannot hide): slope, its error, the two-sided p; nan when a seed has
    fewer than three periods"""
    b, e = [], []
    for y, t in groups:
        if len(y) < 3:
            return math.nan, math.nan, math.nan
        tc = t - t.mean()
        bs = float((tc * (y - y.mean())).sum() / (tc ** 2).sum())
        r = y - y.mean() - bs * tc
        b.append(bs)
        e.append(math.sqrt(float((r ** 2).sum()) / (len(y) - 2) / (tc ** 2).sum()))
    s = seed_mean(b, e)
    dof = s["dof"] if s["dof"] is not None else len(groups[0][0]) - 2
    return s["value"], s["err"], (t_sf2(abs(s["value"]) / s["err"], dof) if s["err"] > 0 else 0.0)


def settle_test(groups, means):
    """no drift of the period means of every seed (groups: (means, mid-times) per seed), and one
    ⟨T⟩ for all seeds (means: (⟨T⟩, its error from τ_int) per seed, compared by independent
    contrasts): Bonferroni over the two; the thesis sizes neither, so it can disagree, never
    agree. The verdict, the drift and its error"""
    b, sb, pa = drift(groups)
    parts = [pa] if math.isfinite(pa) else []
    length = float(groups[0][1][1] - groups[0][1][0]) if len(groups[0][1]) > 1 else math.nan
    text = f"drift of the {length:.3g}-s means {b:.2g} ± {sb:.2g} m²/s³ (p = {pa:.2g})"
    if len(means) > 1:
        T, E = np.array([m for m, _ in means]), np.array([e for _, e in means])
        w = 1 / E ** 2  # weighted Helmert contrasts: n − 1 independent unit normals
        z = [(T[k] - (w[:k] * T[:k]).sum() / w[:k].sum()) / math.sqrt(E[k] ** 2 + 1 / w[:k].sum())
             for k in range(1, len(T))]
        g, pb = chi2_consistent(z, np.ones(len(z)), label="contrasts between the seeds' ⟨T⟩")
        parts.append(pb)
        text += "; " + g.reason.split(";")[0] + f" (p = {pb:.2g})"
    if not parts:
        raise Missing("too few periods for a drift and a single seed")
    return decide(min(1.0, len(parts) * min(parts)), math.nan,
                  "T is steady after the relaxation: its period means drift by zero and every "
                  "seed has one mean", "none sized by the thesis (“approximately 200 seconds”)",
                  text + (f"; Bonferroni over {len(parts)} tests" if len(parts) > 1 else "")
                  + "; the starts: one (equal spacing) from every seed, where Fig. 2.7 compares "
                  "a uniform spread with one cluster (N = 1000)", math.nan), b, sb


def c_settle(d, sw="ring_n512"):
    runs = _runs(d, sw)
    seeds = [q for r in runs for q in r["runs"]]
    series = []  # T(t) of each seed's steady samples in blocks: exact period means and spreads
    for q in seeds:
        try:
            b = t_blocks(q["adir"])
        except Missing:
            raise Missing(f"analysis/{sw}/{q['label']}/temperature_blocks.csv is missing")
        s = b["steady"]
        if s.sum() < 1:
            raise Missing(f"analysis/{sw}/{q['label']}: no steady sample")
        series.append((q, b, b["t"][s], b["T"][s], b["n"][s]))
    span = min(float(b["end"] - t[0]) for _, b, t, _, _ in series)
    length = BLOCK if span >= 2 * BLOCK else span / 4
    groups = [_periods(t, T, n, b["end"], length) for _, b, t, T, n in series]
    if min(len(y) for y, _ in groups) < 3:
        raise Missing(f"analysis/{sw}: runs of {span:.3g} s sampled hold fewer than three periods")
    v, bs, sb = settle_test(groups, [pooled(b, b["steady"])[:2] for _, b, *_ in series])
    v = _gate(v, runs)
    settle, rel200, taus, curves = [], [], [], []
    for q, b, t, T, n in series:
        m, e, sd, _ = pooled(b, b["steady"])
        run = np.cumsum(n * T) / np.cumsum(n)  # the running average at each block's last sample
        curves.append(t + (n - 1) * b["dt"])
        taus.append(b["tau"] * b["dt"])
        out = np.abs(run - m) > 1.96 * e
        settle.append(float(t[np.nonzero(out)[0][-1] + 1]) if out.any() and not out[-1] else
                      (float(t[0]) if not out.any() else math.nan))
        # the relative error a 200-s average would have: Var T and τ_int of this run
        rel200.append(float(sd * math.sqrt(2 * taus[-1] / 200.0) / m))

    def draw(ax):
        for k, ((q, _, _, T, n), (y, tm), tr) in enumerate(zip(series, groups, curves)):
            ax.plot(tm, y, "o", color=f"C{k}", ms=4, label=f"{q['name']}: {length:.3g}-s means")
            step = max(1, len(T) // 2000)
            run = np.cumsum(n * T) / np.cumsum(n)
            ax.plot(tr[::step], run[::step], "-", color=f"C{k}", lw=1)
        ax.axvline(200.0, color="C3", ls="--", label="thesis Fig. 2.8: ≈ 200 s to settle")
        ax.plot([], [], "k-", lw=1, label="running average from the end of the relaxation")
        _ax(ax, f"1D ring, N = {runs[0]['particles']:g}, ε = {runs[0]['eps_n']:g}: T(t) "
            "(thesis Figs. 2.7–2.8)", "t (s)", "T (m²/s²)", fs=7)
    return dict(measured=f"{len(series)} seed{'s' if len(series) > 1 else ''}, {span:.3g} s sampled after {series[0][2][0]:.3g} s: "
                f"τ_int of T {np.mean(taus):.2g} s; the running average stays inside its final 95 % "
                "interval from t = " + ", ".join(f"{x:.3g}" for x in settle) + " s; a 200-s average's "
                "relative error (from Var T and τ_int) " + ", ".join(f"{100 * x:.2g} %" for x in rel200),
                verdict=v, chart=_chart(d, "T-ring-settle", draw),
                values=dict(tau_s=float(np.mean(taus)), drift=bs, drift_err=sb,
                            settle_s=float(np.nanmax(settle)) if np.isfinite(settle).any() else None))

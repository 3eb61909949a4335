"""The thesis' 2D fluid claims beyond D_f: the pair correlation g(R) (§4.2, Fig. 4.7), the velocity
moments against φ (§5.1, Fig. 5.2), the tail exponent α against φ (Tables 5.1–5.2) and the
crossover fit P₀(v) (§5.3.4, Tables 5.3–5.4), against DIR/analysis/<sweep> of `gransim
reproduce rfm`. Each verdict's rule is a function of numbers alone, for the falsification twins."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from .rfm_data import Missing, _ax, _chart, _ci, _csv, _gate, _runs, seed_mean, seed_text  # noqa: E402
from .verdicts import (AGREES, DISAGREES, P_REJECT, UNRESOLVED, Verdict, chi2_consistent,  # noqa: E402
                       compare_value, decide, phi, t_of, t_sf2)


def need(d, path):
    """_csv of a file the claim needs; its absence named relative to DIR"""
    if not os.path.exists(path):
        raise Missing(f"{os.path.relpath(path, d)} is missing")
    return _csv(path)


def point_at(d, sw, phi):
    """the sweep's point nearest the thesis' φ (a sweep over N at fixed L holds several)"""
    return min(_runs(d, sw), key=lambda r: abs(r["phi"] - phi))


def value_p(measured, err, source, source_err=0.0, tolerance=0.0, dof=None):
    """compare_value's p: the excess beyond the tolerance over the combined error"""
    sd = math.hypot(err, source_err)
    x = max(abs(measured - source) - tolerance, 0.0) / sd
    return (t_sf2(x, dof) if x > 0 else 1.0) if dof is not None else 2 * (1 - phi(x))


def all_of(parts, label):
    """one verdict from several tests that must all hold, parts (name, Verdict, p): disagrees
    when the smallest p is below 1 % over their number (Bonferroni: the family's rate stays at
    1 %), agrees when every one agrees, its power the smallest (each has its own alternative)"""
    vs = [v for _, v, _ in parts]
    if min(p for _, _, p in parts) * len(parts) < P_REJECT:
        word = DISAGREES
    elif all(v.verdict == AGREES for v in vs):
        word = AGREES
    else:
        word = UNRESOLVED
    pw = [v.power for v in vs]
    power = min(pw) if all(math.isfinite(p) for p in pw) else float("nan")
    ats = [v.power_at for v in vs]
    at = (lambda k: min(a(k) for a in ats)) if all(ats) else None
    return Verdict(word, "; ".join(f"{n}: {v.reason}" for n, v, _ in parts) +
                   (f" (disagreement needs p < 1 %/{len(parts)} in one of them)" if len(parts) > 1
                    else ""), " and ".join(v.null for v in vs), f"{label}: " + "; ".join(
                       f"{n} {v.alternative}" for n, v, _ in parts), power, float("nan"), at)


def value_part(name, measured, err, source, tolerance, alternative, precision, dof=None):
    """(name, compare_value's verdict, its p) for all_of"""
    return (name, compare_value(measured, err, source, tolerance=tolerance, alternative=alternative,
                                precision=precision, fmt="{:.4g}", dof=dof),
            value_p(measured, err, source, tolerance=tolerance, dof=dof))


# ---- g(R): the large-R level of Fig. 4.7 ------------------------------------------------------

GR_LEVEL, GR_TOL, GR_ALT = 0.98, 0.005, 0.01  # Fig. 4.7's constant fit, printed to two decimals


def gr_level(R, g, e, rmax):
    """the weighted mean of g(R) over the upper half of the recorded range, R ∈ [R_max/2, R_max)
    (the flat large-R part of Fig. 4.7; the runs record g to R_max = L/4), and its error"""
    m = (R >= rmax / 2) & (R < rmax) & (e > 0) & np.isfinite(g)
    if m.sum() < 2:
        raise Missing(f"g(R) has fewer than two bins in [{rmax / 2:g}, {rmax:g}) m")
    w = 1 / e[m] ** 2
    return float((w * g[m]).sum() / w.sum()), float(w.sum() ** -0.5)


def _rmax(R):
    """the outer edge of equal-width bins centred at R"""
    return float(R[-1] + (R[-1] - R[-2]) / 2)


def gr_verdict(level, err, dof=None):
    return compare_value(level, err, GR_LEVEL, tolerance=GR_TOL, alternative=GR_ALT,
                         precision="0.98 printed to two decimals", fmt="{:.4g}", dof=dof)


def gr_decay(R, g, e, lo, hi):
    """eq. 4.11, g = c + A R^(−γ), fitted on lo ≤ R < hi: γ by a profile of χ² over a grid (c and
    A linear at each γ), its 1σ range where χ² rises by χ²_r (at least 1); (γ, lo, hi) or None"""
    m = (R >= lo) & (R < hi) & (e > 0) & np.isfinite(g)
    if m.sum() < 4:
        return None
    x, y, s = R[m], g[m], e[m]
    grid = np.linspace(0.02, 3.0, 150)
    chi = []
    for gam in grid:
        a = np.vstack([np.ones_like(x), x ** -gam]).T / s[:, None]
        sol, *_ = np.linalg.lstsq(a, y / s, rcond=None)
        chi.append(float(((a @ sol - y / s) ** 2).sum()))
    chi = np.array(chi)
    k = int(np.argmin(chi))
    rise = max(1.0, chi[k] / max(m.sum() - 3, 1))
    ok = grid[chi <= chi[k] + rise]
    return float(grid[k]), float(ok.min()), float(ok.max())


def c_gr(d, sw="structure"):
    r = point_at(d, sw, 0.530)
    box = r["info"].get("box", 0.2)
    curves, levels = [], []
    for q in r["runs"]:
        c = need(d, os.path.join(q["adir"], "gr.csv"))[0]
        curves.append(c)
        levels.append(gr_level(c["R"], c["g"], c["g_err"], _rmax(c["R"])))
    s = seed_mean([x[0] for x in levels], [x[1] for x in levels])
    v = gr_verdict(s["value"], s["err"], s["dof"])
    c0 = curves[0]
    R = c0["R"]
    g = np.mean([c["g"] for c in curves], axis=0) if all(len(c["R"]) == len(R) for c in curves) else c0["g"]
    e = np.sqrt(np.sum([c["g_err"] ** 2 for c in curves], axis=0)) / len(curves) \
        if all(len(c["R"]) == len(R) for c in curves) else c0["g_err"]
    rmax = _rmax(R)
    dfs = [(q.get("structure") or {}).get("D_f") for q in r["runs"]]
    df = float(np.mean([x for x in dfs if x is not None])) if any(x is not None for x in dfs) else None
    dec = gr_decay(R, g, e, rmax / 4, rmax)  # past the first shells of contacts (d = 3 mm)
    decay = ""
    if dec:
        decay = (f"; eq. 4.11 fitted on R ∈ [{rmax / 4:.3g}, {rmax:.3g}) m gives γ = {dec[0]:.2f} "
                 f"(1σ range {dec[1]:.2f}…{dec[2]:.2f})")
        if df is not None:
            decay += f", eq. 4.14 with the runs' S(k) D_f = {df:.3g} predicts γ = 2 − D_f = {2 - df:.2f}"
    reason = (f"{v.reason}; level the weighted mean of g over R ∈ [{rmax / 2:.3g}, {rmax:.3g}) m at "
              f"L = {box:g} m; the thesis finds the level size-dependent (\"need not be one and "
              "appears to be affected by the finite size\"), and gives eq. 4.14's decay no number "
              f"(\"very difficult to reliably measure\"){decay}")

    def draw(fig):
        a1, a2 = fig.add_subplot(121), fig.add_subplot(122)
        a1.plot(R, g, "k", lw=0.8, label="gransim g(R)")
        a1.axhline(1.0, color="grey", ls=":")
        a1.set_ylim(0.5, max(float(np.nanmax(g)) * 1.2, 2))
        _ax(a1, f"g(R), φ = {r['phi']:.3g}, L = {box:g} m (thesis Fig. 4.7: L = 0.4 m)", "R (m)",
            "g(R)", False, True, 7)
        z = R >= rmax / 4
        a2.errorbar(R[z], g[z], 1.96 * e[z], fmt=".", ms=3, lw=0.6, color="k", label="gransim, 95 %")
        a2.axhline(GR_LEVEL, color="C3", ls="--", label="thesis Fig. 4.7: constant fit 0.98")
        h = s["err"] * (t_of(0.05, s["dof"]) if s["dof"] else 1.96)
        a2.axhspan(s["value"] - h, s["value"] + h, color="C0",
                   alpha=0.25, label=f"level over [R_max/2, R_max): {_ci(s['value'], s['err'], s['dof'])}")
        a2.axvspan(rmax / 2, rmax, color="C0", alpha=0.06)
        _ax(a2, "large R: the level against the thesis' 0.98", "R (m)", "g(R)", fs=7)
    return dict(measured=f"g(R) level over R ∈ [{rmax / 2:.3g}, {rmax:.3g}) m = "
                f"{_ci(s['value'], s['err'], s['dof'])} (95 %) at L = {box:g} m" + seed_text(s),
                verdict=_gate(Verdict(v.verdict, reason, v.null, v.alternative, v.power, v.scale_,
                                      v.power_at), [r]),
                chart=_chart(d, "g-R", draw, wide=True),
                values=dict(g_level=s["value"], g_level_err=s["err"],
                            gamma=dec[0] if dec else None, D_f=df))


# ---- velocity moments against φ (Fig. 5.2) ------------------------------------------------------

ORDERS = (3, 6, 9, 12)   # the moments Fig. 5.2 shows
PHI_MF = 0.1             # eq. 5.3 holds "for low packing fraction of less than 0.1"


def _moments(d, q):
    """⟨|v|^m⟩ and errors of one run: the velocity components (§5.1's v) where the run has them"""
    p = os.path.join(q["adir"], "moments_components.csv")
    c = need(d, p if os.path.exists(p) else os.path.join(q["adir"], "moments.csv"))[0]
    return {int(m): (x, e) for m, x, e in zip(c["m"], c["moment"], c["error"])}


def mf_slopes(phis, y, e):
    """the slope b_m of ln y_m against ln φ over the points (y_m = ⟨|v|^m⟩^(3/m)), each with its
    error: {m: (b, σ_b)}"""
    lp = np.log(phis)
    out = {}
    for m in y:
        ly, s = np.log(y[m]), e[m] / y[m]
        w = 1 / s ** 2
        xm = (w * lp).sum() / w.sum()
        sxx = (w * (lp - xm) ** 2).sum()
        b = float((w * (lp - xm) * ly).sum() / sxx)
        out[m] = (b, float(sxx ** -0.5))
    return out


def mf_verdict(slopes):
    """eq. 5.3 for every order: slope −1, no precision stated (it can disagree, never agree);
    the four orders share their samples, so the smallest p is Bonferroni-corrected"""
    z = {m: abs(b + 1) / s for m, (b, s) in slopes.items()}
    p = min(1.0, len(z) * min(2 * (1 - phi(x)) for x in z.values()))
    text = ("slopes of ln⟨|v|^m⟩^(3/m) against ln φ: " + ", ".join(
        f"m = {m}: {b:.3f} ± {s:.3f}" for m, (b, s) in slopes.items()) +
        " against eq. 5.3's −1 (the thesis states no precision: the measurement's error alone; the "
        "smallest p of the orders × their number)")
    return decide(p, float("nan"), "⟨|v|^m⟩^(3/m) ∝ 1/φ for every m (eq. 5.3)",
                  "none sized by the thesis", text, float("nan"))


def c_moments_phi(d, sw="moments_phi"):
    pts = sorted(_runs(d, sw), key=lambda r: r["phi"])
    phis, y, e, seeds = [], {m: [] for m in ORDERS}, {m: [] for m in ORDERS}, []
    for r in pts:
        ms = [_moments(d, q) for q in r["runs"]]
        phis.append(r["phi"])
        for m in ORDERS:
            if any(m not in x for x in ms):
                raise Missing(f"analysis/{sw}/{r['label']}: no ⟨|v|^{m}⟩ in its moments")
            s = seed_mean([x[m][0] for x in ms], [x[m][1] for x in ms])
            y[m].append(s["value"] ** (3 / m))
            e[m].append(s["value"] ** (3 / m) * (3 / m) * s["err"] / s["value"])
        seeds.append(len(ms))
    phis = np.array(phis)
    y, e = {m: np.array(v) for m, v in y.items()}, {m: np.array(v) for m, v in e.items()}
    low = phis < PHI_MF
    rel = {m: phis * y[m] / (phis[0] * y[m][0]) for m in ORDERS}  # φ⟨|v|^m⟩^(3/m), 1 in mean field
    dev = "; φ·⟨|v|^m⟩^(3/m) relative to φ = {:.3g}: ".format(phis[0]) + "; ".join(
        f"m = {m}: " + ", ".join(f"{x:.2f}" for x in rel[m][1:]) for m in ORDERS) + \
        " at φ = " + ", ".join(f"{p:.3g}" for p in phis[1:]) + " (1 in mean field)"
    if low.sum() < 2:
        v = Verdict(UNRESOLVED, f"{low.sum()} point(s) below φ = {PHI_MF:g} where eq. 5.3 holds "
                    "(the thesis' Fig. 5.2 spans φ = 0.0014…0.1 there): its slope needs two",
                    "⟨|v|^m⟩^(3/m) ∝ 1/φ for every m (eq. 5.3)", "none sized by the thesis")
        meas = "no slope below φ = 0.1"
    else:
        sl = mf_slopes(phis[low], {m: y[m][low] for m in ORDERS}, {m: e[m][low] for m in ORDERS})
        v = mf_verdict(sl)
        meas = "slopes below φ = 0.1: " + ", ".join(f"m = {m}: {_ci(*sl[m])}" for m in ORDERS)
    v = Verdict(v.verdict, v.reason + "; the departure above φ = 0.1 that Fig. 5.2 shows has no "
                "size in the thesis, so it is reported, not judged", v.null, v.alternative,
                v.power, v.scale_, v.power_at)

    def draw(ax):
        for k, m in enumerate(ORDERS):
            ax.errorbar(phis, y[m], 1.96 * e[m], fmt="os^D"[k], color=f"C{k}", ms=4, capsize=3,
                        label=f"⟨|v|^{m}⟩^(3/{m})")
            pp = np.geomspace(phis.min() * 0.8, phis.max() * 1.2, 20)
            ax.plot(pp, y[m][0] * phis[0] / pp, color=f"C{k}", ls="--", lw=0.8)
        ax.axvspan(phis.min() * 0.8, PHI_MF, color="grey", alpha=0.12, label="φ < 0.1: eq. 5.3")
        _ax(ax, "velocity moments against φ, ε = 0.1 (thesis Fig. 5.2);\ndashed: A/φ through the "
            "lowest φ", "φ", "⟨|v|^m⟩^(3/m) (m³/s³)", True, True, 7)
    return dict(measured=meas + dev + (f"; each point the mean of {max(seeds)} seeds" if max(seeds) > 1
                                       else ""),
                verdict=_gate(v, pts), chart=_chart(d, "moments-phi", draw),
                values={f"rel_m{m}_phi_max": float(rel[m][-1]) for m in ORDERS})


# ---- α against φ (Tables 5.1–5.2) ----------------------------------------------------------------

# (α, the half-width of the accepted range) at L = 0.2 m, ε_n = ε_t = 0.1: Table 5.2's L = 0.2 m
# column where it has the φ, else Table 5.1's first column (its header ε = 0.01 read as 0.1)
ALPHA_PHI = {0.088: (1.53, 0.08), 0.177: (1.45, 0.05), 0.265: (1.43, 0.08), 0.353: (1.30, 0.10),
             0.442: (1.25, 0.35), 0.530: (1.10, 0.15), 0.619: (1.10, 0.10), 0.707: (1.18, 0.03),
             0.795: (1.18, 0.03)}


def thesis_alpha(p):
    for k, v in ALPHA_PHI.items():
        if abs(p - k) <= 5e-4:
            return k, v
    return None, None


def pooled_alpha(tails):
    """the midpoint of the runs' accepted ranges, weighted by their half-widths read as 2σ (as
    claim alpha-structure), and its error; None when no run accepts an α"""
    acc = [t for t in tails if t and t.get("accepted") and t.get("alpha_lo") is not None]
    if not acc:
        return None
    mids = np.array([(t["alpha_lo"] + t["alpha_hi"]) / 2 for t in acc])
    w = 1 / np.array([max((t["alpha_hi"] - t["alpha_lo"]) / 4, 0.005) for t in acc]) ** 2
    return float((w * mids).sum() / w.sum()), float(w.sum() ** -0.5), len(acc)


def alpha_phi_verdict(meas, src):
    """χ² of the points' α against the thesis' at each φ, both ranges read as 95 % intervals;
    the alternative: every point off by the thesis' half-width there"""
    res = [m - s for (m, _), (s, _) in zip(meas, src)]
    err = [math.hypot(e, h / 2) for (_, e), (_, h) in zip(meas, src)]
    v, _ = chi2_consistent(res, err, "differences from the tables", alternative=[h for _, h in src],
                           alt_text="every point off by the thesis' half-width there")
    return v


def c_alpha_phi(d, sw="moments_phi"):
    pts = sorted(_runs(d, sw), key=lambda r: r["phi"])
    rows, meas, src, skipped = [], [], [], []
    for r in pts:
        k, s = thesis_alpha(r["phi"])
        a = pooled_alpha([q.get("tail") for q in r["runs"]])
        best = [q["tail"]["alpha_best"] for q in r["runs"] if q.get("tail")]
        rows.append((r["phi"], a, s, float(np.mean(best)) if best else None))
        if s is None:
            skipped.append(f"φ = {r['phi']:.3g}: not in the tables")
        elif a is None:
            skipped.append(f"φ = {r['phi']:.3g}: no α passes χ²_r < 1.2")
        else:
            meas.append(a[:2])
            src.append(s)
    if not meas:
        v = Verdict(UNRESOLVED, "no point has an accepted α at a φ of the tables" +
                    (" (" + "; ".join(skipped) + ")" if skipped else ""))
    else:
        v = alpha_phi_verdict(meas, src)
        if skipped:
            v = Verdict(v.verdict, v.reason + "; left out: " + "; ".join(skipped), v.null,
                        v.alternative, v.power, v.scale_, v.power_at)

    def draw(ax):
        t = sorted(ALPHA_PHI.items())
        ax.errorbar([x for x, _ in t], [a for _, (a, _) in t], [h for _, (_, h) in t], fmt="s",
                    color="C3", capsize=3, mfc="none", label="thesis (Tables 5.2, 5.1), ± its range")
        ok = [(p, a) for p, a, _, _ in rows if a]
        if ok:
            ax.errorbar([p for p, _ in ok], [a[0] for _, a in ok], [1.96 * a[1] for _, a in ok],
                        fmt="o", color="C0", capsize=3, label="gransim, pooled over seeds, 95 %")
        no = [(p, b) for p, a, _, b in rows if not a and b is not None]
        if no:
            ax.plot([p for p, _ in no], [b for _, b in no], "x", color="C0", ms=8,
                    label="gransim best α where none passes χ²_r < 1.2 (seeds' mean)")
        ax.axhspan(1.163 - 0.017, 1.163 + 0.017, color="C3", alpha=0.15,
                   label="upper limit 1.163 ± 0.017 (φ ≳ 0.53)")
        _ax(ax, "tail exponent α against φ, L = 0.2 m, ε = 0.1", "φ", "α", fs=7)
    return dict(measured="accepted α: " + "; ".join(
        f"φ = {p:.3g}: " + (f"{_ci(a[0], a[1])} ({a[2]} run(s))" if a else "none") +
        (f" (thesis {s[0]:.2f} ± {s[1]:.2f})" if s else "") for p, a, s, _ in rows) + " (95 %)",
                verdict=_gate(v, pts), chart=_chart(d, "alpha-phi", draw),
                values={f"alpha_{p:.3f}": a[0] for p, a, _, _ in rows if a})


# ---- the crossover fit P₀(v) (Tables 5.3–5.4) ----------------------------------------------------

# Table 5.3 (ε_t = 0.1) and 5.4 (ε_t = 1): (ε_n, ε_t) -> (v_r in m/s, v_c/v_r)
CROSSOVER = {(0.1, 0.1): (0.168, 1.524), (0.2, 0.1): (0.177, 1.540), (0.3, 0.1): (0.186, 1.743),
             (0.4, 0.1): (0.198, 1.914), (0.5, 0.1): (0.213, 2.141), (0.6, 0.1): (0.231, 2.463),
             (0.7, 0.1): (0.253, 2.927), (0.8, 0.1): (0.282, 3.784), (0.9, 0.1): (0.318, 5.100),
             (0.2, 1.0): (0.337, 3.877), (0.3, 1.0): (0.344, 4.107), (0.4, 1.0): (0.352, 4.469),
             (0.5, 1.0): (0.365, 5.133), (0.6, 1.0): (0.389, 6.469), (0.7, 1.0): (0.422, 9.592),
             (0.8, 1.0): (0.481, 23.037)}


def p0(v, dd, vr, vc):
    """T.5.32 with α = 1: D exp(−(v/v_r)²/(1 + |v/v_c|))"""
    return dd * np.exp(-(v / vr) ** 2 / (1 + np.abs(v / vc)))


def fit_p0(v, P, s):
    """D, v_r, v_c of T.5.32 at α = 1 (the thesis' choice) by Levenberg–Marquardt on ln P with
    the bins' relative errors; (params, their errors scaled by √χ²_r when > 1, χ²_r)"""
    y, w = np.log(P), P / s
    var = float((P * v * v).sum() / P.sum())
    x = np.array([math.log(P.max()), math.log(math.sqrt(2 * var)), math.log(1.5 * math.sqrt(2 * var))])

    def f(x):
        return (np.log(p0(v, math.exp(x[0]), math.exp(x[1]), math.exp(x[2]))) - y) * w
    lam, r = 1e-3, f(x)
    for _ in range(200):
        J = np.empty((len(v), 3))
        for i in range(3):
            h = np.zeros(3)
            h[i] = 1e-6
            J[:, i] = (f(x + h) - r) / 1e-6
        A = J.T @ J
        step = np.linalg.solve(A + lam * np.diag(np.diag(A)), -J.T @ r)
        r2 = f(x + step)
        if (r2 ** 2).sum() < (r ** 2).sum():
            x, r, lam = x + step, r2, lam / 3
            if np.abs(step).max() < 1e-9:
                break
        else:
            lam *= 4
    dof = max(len(v) - 3, 1)
    chi2r = float((r ** 2).sum() / dof)
    cov = np.linalg.inv(J.T @ J) * max(chi2r, 1.0)
    p = np.exp(x)
    return p, p * np.sqrt(np.diag(cov)), chi2r  # d(eˣ) = eˣ dx


def crossover_verdict(vr, e_vr, ratio, e_ratio, key=(0.1, 0.1), dof=None):
    """v_r and v_c/v_r against the table's row, each printed to three decimals; the alternative:
    the step to the neighbouring row of ε_n (the smallest difference the tables resolve)"""
    s_vr, s_ratio = CROSSOVER[key]
    nb = [CROSSOVER[k] for k in CROSSOVER if k[1] == key[1] and abs(k[0] - key[0]) < 0.101
          and k != key]
    a_vr = min(abs(x[0] - s_vr) for x in nb)
    a_ratio = min(abs(x[1] - s_ratio) for x in nb)
    prec = "printed to three decimals"
    return all_of([value_part("v_r", vr, e_vr, s_vr, 0.0005, a_vr, prec, dof),
                   value_part("v_c/v_r", ratio, e_ratio, s_ratio, 0.0005, a_ratio, prec, dof)],
                  f"the neighbouring row of Table {'5.3' if key[1] == 0.1 else '5.4'}")


def c_crossover(d, sw="structure"):
    r = point_at(d, sw, 0.530)
    key = (round(r["eps_n"], 3), round(r["eps_t"], 3))
    if key not in CROSSOVER:
        raise Missing(f"analysis/{sw}: ε = {key[0]:g}/{key[1]:g} is in neither Table 5.3 nor 5.4")
    fits = []
    for q in r["runs"]:
        c = need(d, os.path.join(q["adir"], "velocity.csv"))[0]
        m = (c["count"] >= 10) & (c["P"] > 0)
        fits.append(fit_p0(c["v"][m], c["P"][m], c["P_err"][m]) + (c,))
    vr = seed_mean([f[0][1] for f in fits], [f[1][1] for f in fits])
    rt = seed_mean([f[0][2] / f[0][1] for f in fits],
                   [f[0][2] / f[0][1] * math.hypot(f[1][1] / f[0][1], f[1][2] / f[0][2]) for f in fits])
    v = crossover_verdict(vr["value"], vr["err"], rt["value"], rt["err"], key, vr["dof"])
    chi = max(f[2] for f in fits)
    v = Verdict(v.verdict, v.reason + f"; T.5.32 at α = 1 fitted on bins of ≥ 10 counts, χ²_r ≤ "
                f"{chi:.3g} (the samples are correlated, so the seeds' scatter carries the error); "
                "Table 5.4 (ε_t = 1) needs runs of ε_t = 1, which no plan has", v.null,
                v.alternative, v.power, v.scale_, v.power_at)
    s_vr, s_ratio = CROSSOVER[key]

    def draw(ax):
        (pp, _, _, c) = fits[0]
        z = c["P"] > 0
        ax.errorbar(c["v"][z], c["P"][z], c["P_err"][z], fmt=".", ms=2, lw=0.5, color="k",
                    label="gransim P(v) (first seed)")
        vv = np.linspace(c["v"].min(), c["v"].max(), 400)
        ax.plot(vv, p0(vv, pp[0], pp[1], pp[2]), "C0",
                label=f"T.5.32 fit: v_r = {pp[1]:.3f}, v_c/v_r = {pp[2] / pp[1]:.3f}")
        ax.plot(vv, p0(vv, pp[0], s_vr, s_vr * s_ratio), "C3--",
                label=f"Table 5.3 row {key[0]:g}, {key[1]:g}: v_r = {s_vr}, v_c/v_r = {s_ratio}")
        ax.set_ylim(max(c["P"][z].min() / 3, 1e-7), c["P"].max() * 3)
        _ax(ax, f"crossover P₀(v), α = 1, φ = {r['phi']:.3g}, L = {r['info'].get('box', 0.2):g} m "
            "(thesis Fig. 5.14a)", "v (m/s)", "P(v) (s/m)", False, True, 7)
    return dict(measured=f"v_r = {_ci(vr['value'], vr['err'], vr['dof'])} m/s, v_c/v_r = "
                f"{_ci(rt['value'], rt['err'], rt['dof'])} (95 %) at ε = {key[0]:g}/{key[1]:g}" + seed_text(vr),
                verdict=_gate(v, [r]), chart=_chart(d, "crossover", draw),
                values=dict(v_r=vr["value"], v_r_err=vr["err"], vc_vr=rt["value"],
                            vc_vr_err=rt["err"]))

"""The thesis' 1D claims at ε = 0.1 (velocity-moment exponents ξ_m, the velocity PDFs' collapse,
the gaps' exponents ζ_m and their distribution against the bisection process) against
DIR/analysis/ring of `gransim reproduce rfm`."""
import math
import os

import matplotlib

matplotlib.use("Agg")
import numpy as np  # noqa: E402

from .rfm_conditions import THESIS  # noqa: E402
from .verdicts import (DISAGREES, P_KEEP, P_REJECT, UNRESOLVED, Verdict, chi2_sf,  # noqa: E402
                       compare_value, decide, phi, power_two_sided, t_sf2)

from .rfm_data import (CUT, N_THESIS, Missing, _csv, _runs, _ci, _gate, _chart, _ax, _wfit,  # noqa: E402
                       seed_mean)


def _by_size(c):
    """moments_vs_N.csv's rows with the runs of one (dimension, ε, N, m) (its seeds) merged by
    seed_mean (⟨|v|^m⟩ and ⟨R^m⟩ each), in the order of their first row; rows of one run each
    stay as they are"""
    keys = list(zip(c["dimension"], c["eps_n"], c["N"], c["m"]))
    groups = {}
    for i, k in enumerate(keys):
        groups.setdefault(k, []).append(i)
    if all(len(g) == 1 for g in groups.values()):
        return c
    pairs = [p for p in (("v_moment", "v_err"), ("R_moment", "R_err")) if p[0] in c]
    out = {k: [] for k in ("dimension", "eps_n", "N", "m", "seeds", "dof")}
    out.update({k: [] for p in pairs for k in p})
    for (dim, e, n, m), g in groups.items():
        for k, x in zip(("dimension", "eps_n", "N", "m", "seeds"), (dim, e, n, m, len(g))):
            out[k].append(x)
        for val, err in pairs:
            s = seed_mean(c[val][g], c[err][g])
            out[val].append(s["value"])
            out[err].append(s["err"])
        out["dof"].append(math.nan if len(g) < 2 else len(g) - 1)
    return {k: np.array(v, float) for k, v in out.items()}


def point_dofs(c, k):
    """the degrees of freedom of the errors of a moments() table's rows k (seeds − 1; None for
    a row of one run, whose error is the run's own)"""
    if "dof" not in c:
        return [None] * int(np.count_nonzero(k))
    return [None if not np.isfinite(x) else float(x) for x in c["dof"][k]]


def _table(d, sw):
    """analysis/<sw>/moments_vs_N.csv as it is (every seed's rows)"""
    p = os.path.join(d, "analysis", sw, "moments_vs_N.csv")
    if not os.path.exists(p):  # the folder's own name, not this machine's path
        raise Missing(f"analysis/{sw}/moments_vs_N.csv is missing")
    return _csv(p)[0]


def moments(d, sw):
    """analysis/<sw>/moments_vs_N.csv with each point's moments the mean over its seeds"""
    return _by_size(_table(d, sw))


def exponents(c, eps, ms, col="v_moment", n_from=N_THESIS):
    """the exponents of col ∝ N^(−x) at ε (moments' or gaps' ⟨·^m⟩ of moments()) fitted over the
    sizes N ≥ n_from (all when fewer than two): the sizes, whether they are the thesis', and
    {m: (x, σ_x, ln amplitude, χ², the fit's degrees of freedom, the t test's on x (slope_dof;
    None when no size's error is a seed scatter))}"""
    err = {"v_moment": "v_err", "R_moment": "R_err"}[col]
    sel = (c["dimension"] == 1) & (np.abs(c["eps_n"] - eps) < 1e-9)
    ns = sorted(set(c["N"][sel]))
    use = [n for n in ns if n >= n_from]
    inside = len(use) >= 2
    use = use if inside else ns
    if len(use) < 2:
        raise Missing(f"ring sizes {ns} at ε = {eps:g}: two are needed to fit an exponent")
    out = {}
    for m in ms:
        k = sel & (c["m"] == m) & np.isin(c["N"], use) & (c[err] > 0) & (c[col] > 0)
        x, y, s = np.log(c["N"][k]), np.log(c[col][k]), c[err][k] / c[col][k]
        if len(x) < 2:
            raise Missing(f"fewer than two sizes with ⟨·^{m}⟩ and its error at ε = {eps:g}")
        b, e, a = _wfit(x, y, s)
        out[m] = (-b, e, a, float((((y - a - b * x) / s) ** 2).sum()), len(x) - 2,
                  slope_dof(x, s, point_dofs(c, k)))
    return use, inside, out


def eps_values(c):
    """the ring's ε values in a moments() table"""
    return sorted({float(e) for e in c["eps_n"][c["dimension"] == 1]})


def _seeds(c):
    """'' when each size ran from one seed; else how its moments' errors were chosen"""
    if "seeds" not in c or c["seeds"].max() < 2:
        return ""
    k = " or ".join(f"{x:g}" for x in sorted(set(c["seeds"])))
    return (f"; each size's ⟨|v|^m⟩ the mean of {k} seeds, its error the larger of the scatter "
            "between seeds and the within-run error")


def _xi(d, sw="ring"):
    """ξ_m of ⟨|v|^m⟩ ∝ N^(−ξ_m), refitted over the thesis' sizes N ≥ 398 (all if fewer than 2);
    each size's moment the mean over its seeds; xi[m] = (ξ_m, σ, ln amplitude, the t test's
    degrees of freedom or None)"""
    runs = _runs(d, sw)
    c = _by_size(_csv(os.path.join(d, "analysis", sw, "moments_vs_N.csv"))[0])
    sel = (c["dimension"] == 1) & (c["eps_n"] == c["eps_n"][c["dimension"] == 1][0])
    ns = sorted(set(c["N"][sel]))
    use = [n for n in ns if n >= N_THESIS]
    inside = len(use) >= 2
    use = use if inside else ns
    if len(use) < 2:
        raise Missing(f"ring sizes {ns}: two are needed to fit ξ_m")
    xi = {}
    for m in range(1, 13):
        k = sel & (c["m"] == m) & np.isin(c["N"], use) & (c["v_err"] > 0)
        x, s = np.log(c["N"][k]), c["v_err"][k] / c["v_moment"][k]
        b, e, a = _wfit(x, np.log(c["v_moment"][k]), s)
        xi[m] = (-b, e, a, slope_dof(x, s, point_dofs(c, k)))
    sizes = ", ".join(f"{n:g}" for n in use)

    def outside(v):
        if inside:
            return v
        face = "" if v.verdict == UNRESOLVED else f"at face value: {v.verdict}, "
        return Verdict(UNRESOLVED, f"sizes N = {sizes} lie below the thesis' fit range N = 398…10⁴; "
                       f"{face}{v.reason}", v.null, v.alternative, v.power, v.scale)
    return runs, c, sel, use, sizes, xi, outside


def c_xi2(d, sw="ring"):
    runs, c, sel, use, sizes, xi, outside = _xi(d, sw)
    x2, e2, a2, dof2 = xi[2]
    v = outside(_gate(compare_value(x2, e2, 0.53, tolerance=0.005, alternative=0.01,
                                    precision="≃ 0.53 printed to two decimals", fmt="{:.3g}",
                                    dof=dof2), runs))

    def draw(ax):
        k = sel & (c["m"] == 2)
        ax.errorbar(c["N"][k], c["v_moment"][k], 1.96 * c["v_err"][k], fmt="o", capsize=3,
                    label="gransim ⟨v²⟩, 95 %")
        nn = np.geomspace(min(c["N"][k]) * 0.8, max(max(c["N"][k]), 1e4) * 1.2, 50)
        nc = math.exp(np.mean(np.log(use)))
        yc = math.exp(a2) * nc ** -x2
        ax.plot(nn, yc * (nn / nc) ** -x2, "C0", label=f"fit ξ₂ = {_ci(x2, e2, dof2)}")
        ax.plot(nn, yc * (nn / nc) ** -0.528, "C3--", label="thesis N^−0.528")
        ax.plot(nn, yc * (nn / nc) ** (-2 / 3), "k:", label="mean field N^−2/3")
        ax.axvspan(nn[0], N_THESIS, color="grey", alpha=0.15, label="sizes the thesis ignored")
        _ax(ax, "1D ring, L′ = 1 m, ε = 0.1 (thesis Figs. 3.1–3.2)", "N", "⟨v²⟩ (m²/s²)", True, True)
    return dict(measured=f"ξ₂ = {_ci(x2, e2, dof2)} (95 %) over N = {sizes}" + _seeds(c), verdict=v,
                chart=_chart(d, "xi2", draw), values=dict(xi2=x2, xi2_err=e2, N_min=min(use),
                                                          N_max=max(use)))


def c_xim(d, sw="ring"):
    runs, c, sel, use, sizes, xi, outside = _xi(d, sw)
    y, e = [xi[1][0], xi[9][0] / 9], [xi[1][1], xi[9][1] / 9]
    # Fig. 3.4b read to three decimals (± 0.0005 at each end); the alternative: no decrease
    v = compare_value(y[1] - y[0], math.hypot(*e), 0.228 - 0.264, tolerance=0.001,
                      alternative=0.036, precision="0.264 and 0.228 read to three decimals",
                      fmt="{:.3g}", dof=fewer_dof(xi[1][3], xi[9][3]))
    v.alternative = "no decrease of ξ_m/m (0.036 from the thesis' change)"
    v = outside(_gate(Verdict(v.verdict, "ξ₉/9 − ξ₁ : " + v.reason, v.null, v.alternative,
                              v.power, v.scale_, v.power_at), runs))

    def draw(ax):
        m = np.arange(1, 13)
        ax.errorbar(m, [xi[k][0] / k for k in m], [1.96 * xi[k][1] / k for k in m], fmt="o",
                    capsize=3, label="gransim ξ_m/m, 95 %")
        ax.plot([1, 9], [0.264, 0.228], "C3s--", label="thesis Fig. 3.4b (ε = 0.001): 0.264 → 0.228")
        ax.axhline(1 / 3, color="k", ls=":", label="mean field 1/3")
        _ax(ax, f"1D ring, ε = 0.1, N = {sizes}", "m", "ξ_m / m")
    return dict(measured=f"ξ₁ = {_ci(*xi[1][:2], xi[1][3])}, ξ₉/9 = {_ci(y[1], e[1], xi[9][3])} (95 %) over N = {sizes}"
                + _seeds(c),
                verdict=v, chart=_chart(d, "xi-m", draw), values=dict(xi1=y[0], xi9_9=y[1]))


def _bis_cdf(x, n):
    """P(X ≤ x) for X a product of n uniforms (−ln X ~ Gamma(n)); n = log₂N need not be whole"""
    return np.array([1.0 if q >= 1 else 0.0 if q <= 0 else chi2_sf(-2 * math.log(q), 2 * n) for q in x])


def _ks_p(lam):
    """Kolmogorov's P(√n D > λ)"""
    return 1.0 if lam < 0.3 else min(1.0, 2 * sum((-1) ** (k - 1) * math.exp(-2 * k * k * lam * lam)
                                                  for k in range(1, 101)))


def c_g1(d, sw="ring"):
    runs = _runs(d, sw)
    at = [q for q in runs if q["particles"] == THESIS["G1-bisection"]["N"]]  # else the largest
    r = at[0] if at else max(runs, key=lambda q: q["particles"])
    N = r["particles"]
    cs = [_csv(os.path.join(x["adir"], "gh_bisection.csv"))[0] for x in r["runs"]]
    c = cs[0]
    R, G, Ge = c["R"], c["G1"], c["G1_err"]  # G1: density per unit R/L′ on log bins (geometric centres)
    if len(cs) > 1:  # the seeds' gaps pooled: the mean of their densities on the same bins
        if any(len(x["R"]) != len(R) or not np.allclose(x["R"], R) for x in cs):
            raise Missing(f"analysis/{sw}: the seeds' gh_bisection.csv have different R bins")
        G = np.mean([x["G1"] for x in cs], axis=0)
        Ge = np.sqrt(np.sum([x["G1_err"] ** 2 for x in cs], axis=0)) / len(cs)
    q = R[1] / R[0]
    lo, hi = R / math.sqrt(q), np.minimum(R * math.sqrt(q), 1.0)
    w, n, keep = hi - lo, math.log2(N), R >= CUT
    pb = (_bis_cdf(hi, n) - _bis_cdf(lo, n)) / w  # bin averages, not the centre values
    pu = ((1 - lo) ** (N - 1) - (1 - hi) ** (N - 1)) / w
    mass = (G * w)[keep].sum()  # both on R ≥ CUT, normalised like G₁ there
    pb, pu = pb * mass / (pb * w)[keep].sum(), pu * mass / (pu * w)[keep].sum()
    gaps, s = 0, 1.0
    for x in r["runs"]:  # gaps counted over every seed; the strongest correlation of any seed
        g = _csv(os.path.join(x["adir"], "gap_moments.csv"))[0]
        M, B = g["moment"], g["error"]
        ng = N * x["info"].get("samples", x["samples"])
        s = max(s, B[1] / math.sqrt((M[3] - M[1] ** 2) / ng))  # correlation: block / iid error of ⟨R²⟩
        gaps += ng
    F = np.cumsum((G * w)[keep]) / mass
    kb, ku = [float(np.abs(F - np.cumsum((p * w)[keep]) / mass).max()) for p in (pb, pu)]
    neff = gaps * mass / s ** 2
    # where the distance lies: the decade above contact (gaps of disks that have just parted or
    # are held together in a cluster), and the distance from there on
    near = (R >= CUT) & (R < 10 * CUT)
    excess = float((G * w)[near].sum() / (pb * w)[near].sum())
    far = R >= 10 * CUT
    m10 = (G * w)[far].sum()
    F10 = np.cumsum((G * w)[far]) / m10
    k10 = float(np.abs(F10 - np.cumsum((pb * w)[far]) / (pb * w)[far].sum()).max())
    # the thesis states no precision for "good agreement": Kolmogorov's test alone, with no
    # power; its claim is for N = 2⁹, so a run of other N says so instead of deciding
    p = _ks_p(math.sqrt(neff) * kb)
    face = "disagrees" if p < P_REJECT else ("not rejected" if p > P_KEEP else "between 1 % and 5 %")
    why = (f"KS distance to the bisection {kb:.2g} with n_eff = {neff:.3g} (the gaps counted over "
           f"{s:.1f}², the ratio of ⟨R²⟩'s block error to its independent-sample error): p = {p:.2g}, "
           f"at face value {face}; the thesis states no precision for its “good agreement”, so no "
           "power")
    if N != THESIS["G1-bisection"]["N"]:
        v = Verdict(UNRESOLVED, why + f"; the claim is made for N = 2⁹ = 512, this run has N = {N:g}",
                    "G₁ is the bisection's distribution", "none sized by the thesis")
    else:
        v = Verdict(DISAGREES if p < P_REJECT else UNRESOLVED, why,
                    "G₁ is the bisection's distribution", "none sized by the thesis")
    v = _gate(v, runs)

    def draw(fig):
        a1, a2 = fig.add_subplot(121), fig.add_subplot(122)
        z = G > 0
        a1.errorbar(R[z], G[z], Ge[z], fmt="x", ms=3, lw=0.6, color="k", label=f"gransim G₁, N = {N:g}")
        a1.plot(R, pb, "C3", label=f"bisection, n = log₂N = {n:.2f} levels (T.3.36)")
        a1.plot(R, pu, "C0--", label=f"{N:g} uniform points")
        a1.axvspan(R[0], CUT, color="grey", alpha=0.15, label="touching disks (overlaps), left out")
        a1.set_ylim(max(G[z].min() / 10, 1e-4), G.max() * 10)
        _ax(a1, "nearest-neighbour gaps against the bisection (thesis Fig. 3.16)", "R (units of L′)",
            "G₁(R) (1/L′)", True, True, 7)
        a2.plot(R[keep], F, "k", label="gransim")
        a2.plot(R[keep], np.cumsum((pb * w)[keep]) / mass, "C3--", label="bisection")
        a2.plot(R[keep], np.cumsum((pu * w)[keep]) / mass, "C0:", label="uniform points")
        _ax(a2, f"cumulative, R ≥ {CUT:g} L′: KS {kb:.3f} (bisection), {ku:.3f} (uniform)",
            "R (units of L′)", "fraction of gaps", True)
    return dict(measured=f"N = {N:g}" + (f" ({len(cs)} seeds pooled)" if len(cs) > 1 else "")
                + f": KS distance of G₁ (R ≥ {CUT:g} L′) {kb:.3f} to the bisection, "
                f"{ku:.3f} to {N:g} uniform points; the decade above contact ({CUT:g}–{10 * CUT:g}"
                f" L′) holds {excess:.2f}× the bisection's gaps, and from {10 * CUT:g} L′ on the "
                f"distance is {k10:.3f} (p = {_ks_p(math.sqrt(neff * m10 / mass) * k10):.2g})",
                verdict=v, chart=_chart(d, "G1-bisection", draw, wide=True),
                values=dict(N=N, ks_bisection=kb, ks_uniform=ku, n_eff=neff,
                            near_contact_excess=excess, ks_bisection_far=k10))


def bonferroni(parts, null, alt, text, joint=False):
    """one verdict from several tests of one claim, parts = (two-sided p, α ↦ (k ↦ the part's
    power at level α and k times the run's length), or None when the part has no alternative):
    p = min(1, n·min p), Bonferroni over the n parts. Its power at level 5 %/n: against an
    alternative that any one part may carry, the smallest of the parts' (it agrees only where
    every sized part could have failed it); against one that all carry at once (joint), the
    largest, a lower bound of the union test's"""
    n = len(parts)
    p = min(1.0, n * min(q for q, _ in parts))
    sized = [f for _, f in parts if f is not None]
    pick = max if joint else min

    def at(k):
        return pick(f(P_KEEP / n)(k) for f in sized) if sized else math.nan
    return decide(p, at(1.0), null, alt, text + (f"; Bonferroni over {n} tests" if n > 1 else ""),
                  math.nan, power_at=at if sized else None)


def _two_sided(x, e, target, tol=0.0, dof=None):
    """P(an estimate x ± e lies this far beyond target ± tol): normal, or Student's t when e is
    a scatter of dof degrees of freedom"""
    z = max(abs(x - target) - tol, 0.0) / e
    if dof is not None:
        return t_sf2(z, dof) if z > 0 else 1.0
    return 2.0 * (1.0 - phi(z))


def fewer_dof(*dofs):
    """the degrees of freedom of a difference of estimates fitted to the same seeds: the fewest
    of theirs (conservative), None when every error is known"""
    d = [x for x in dofs if x is not None]
    return min(d) if d else None


def with_known(e, dof, se):
    """Welch–Satterthwaite degrees of freedom of hypot(e, se), e a scatter of dof degrees of
    freedom and se a known error (None when e is known too)"""
    if dof is None:
        return None
    return (e * e + se * se) ** 2 / (e ** 4 / dof)


# Table 3.1 (ε = 0.1): ζ_m measured, its ±, and the uniform bisection's ln(m + 1)/ln 2 (T.3.38)
ZETA = {2: (1.729, 0.008), 3: (2.31, 0.03), 4: (2.81, 0.06), 5: (3.2, 0.1)}


def zeta_test(c, eps):
    """ζ₂…ζ₅ of a moments() table at ε against Table 3.1: the verdict, the sizes, whether they are
    the thesis' and the fits"""
    use, inside, z = exponents(c, eps, range(1, 7), "R_moment")
    parts, rows = [], []
    for m, (src, se) in ZETA.items():
        x, e, dof = z[m][0], z[m][1], z[m][5]
        s = math.hypot(e, se)
        alt = abs(src - math.log(m + 1) / math.log(2))
        parts.append((_two_sided(x, s, src, dof=with_known(e, dof, se)),
                      lambda a, e=e, se=se, alt=alt, dof=dof: (
            lambda k: power_two_sided(alt, math.hypot(e / math.sqrt(k), se), alpha=a,
                                      dof=with_known(e / math.sqrt(k), dof, se)))))
        rows.append(f"ζ{m} = {_ci(x, e, dof)} (thesis {src:g} ± {se:g}, {abs(x - src) / s:.1f}σ)")
    # the thesis' ± is taken as its standard error: it enters as the source's error, not as a
    # tolerance
    v = bonferroni(parts, "ζ_m = Table 3.1's value (its ± the thesis' standard error), m = 2…5",
                   "the uniform bisection's ζ_m = ln(m + 1)/ln 2, which the thesis says the model "
                   "departs from (1.58, 2, 2.32, 2.58)", "; ".join(rows), joint=True)
    if not inside:
        sizes = ", ".join(f"{n:g}" for n in use)
        face = "" if v.verdict == UNRESOLVED else f"at face value: {v.verdict}, "
        v = Verdict(UNRESOLVED, f"sizes N = {sizes} lie below the thesis' N ≥ 398; {face}{v.reason}",
                    v.null, v.alternative, v.power, v.scale)
    return v, use, inside, z


def c_zeta(d, sw="ring"):
    runs, c = _runs(d, sw), moments(d, sw)
    eps = eps_values(c)[0]
    v, use, inside, z = zeta_test(c, eps)
    sizes = ", ".join(f"{n:g}" for n in use)
    v = _gate(v, runs)

    def draw(ax):
        m = np.arange(1, 7)
        ax.errorbar(m, [z[k][0] for k in m], [1.96 * z[k][1] for k in m], fmt="o", capsize=3,
                    label="gransim ζ_m, 95 %")
        ax.errorbar(list(ZETA), [x for x, _ in ZETA.values()], [1.96 * e for _, e in ZETA.values()],
                    fmt="s", mfc="none", color="C3", capsize=3,
                    label="thesis Table 3.1 (± as 1σ, 95 % bars)")
        ax.plot(m, np.log(m + 1) / math.log(2), "k:", label="uniform bisection ln(m+1)/ln 2")
        _ax(ax, f"gap moments ⟨R^m⟩ ∝ N^−ζ_m, ε = {eps:g}, N = {sizes}", "m", "ζ_m")
    return dict(measured=", ".join(f"ζ{m} = {_ci(*z[m][:2], z[m][5])}" for m in range(1, 6))
                + f" (95 %) over N = {sizes}" + _seeds(c).replace("⟨|v|^m⟩", "⟨R^m⟩"), verdict=v,
                chart=_chart(d, "zeta-m", draw),
                values={f"zeta{m}": z[m][0] for m in range(1, 6)})


# the thesis' ξ_m/m at ε ≤ 0.5 (§3.2.1–3.2.2): ξ₂/2 ≃ 0.264, ξ₅/5 ≃ 0.252, ξ₆/6 ≃ 0.247 and
# Fig. 3.4(b)'s ξ₉/9 = 0.228; ⟨|v|^m⟩/⟨v²⟩^(m/2) ∝ N^(m(ξ₂/2 − ξ_m/m)) then
XI_M = {5: 0.252, 6: 0.247, 9: 0.228}
XI2_2 = 0.264


def rescaled(c, eps, m):
    """ln(⟨|v|^m⟩/⟨v²⟩^(m/2)) of each size at ε from a raw moments_vs_N.csv table (every seed's
    row): each seed's ratio, merged by seed_mean; its error from the two moments' errors taken
    as independent (they are positively correlated, so this is larger than the truth)"""
    sel = (c["dimension"] == 1) & (np.abs(c["eps_n"] - eps) < 1e-9)
    out = {}
    for n in sorted(set(c["N"][sel])):
        a, b = sel & (c["N"] == n) & (c["m"] == m), sel & (c["N"] == n) & (c["m"] == 2)
        y = np.log(c["v_moment"][a]) - m / 2 * np.log(c["v_moment"][b])
        e = np.hypot(c["v_err"][a] / c["v_moment"][a], m / 2 * c["v_err"][b] / c["v_moment"][b])
        out[n] = seed_mean(y, e)
    return out


def vpdf_test(raw, eps):
    """the collapse of the rescaled moments of a raw moments_vs_N.csv table (every seed's rows)
    at ε: the verdict, the moment tested and every moment's (slope, error, thesis' slope, N,
    ln ratio, error)"""
    fits = {}
    for m, xm in XI_M.items():
        r = rescaled(raw, eps, m)
        if len(r) < 2:
            raise Missing(f"{len(r)} ring size at ε = {eps:g}; the collapse needs two")
        n = np.array(sorted(r), float)
        y, e = np.array([r[k]["value"] for k in n]), np.array([r[k]["err"] for k in n])
        b, eb, _ = _wfit(np.log(n), y, e)
        dof = slope_dof(np.log(n), e, [r[k].get("dof") for k in n])
        fits[m] = (b, eb, m * (XI2_2 - xm), n, y, e, dof)
    # the moment whose test has the most power against the thesis' size (chosen on the errors
    # alone, before the slope is looked at)
    m = max(fits, key=lambda k: power_two_sided(fits[k][2], fits[k][1], dof=fits[k][6]))
    b, eb, size = fits[m][:3]
    dof = fits[m][6]
    p = 2.0 * (1.0 - phi(abs(b) / eb)) if dof is None else t_sf2(abs(b) / eb, dof)

    def at(k):
        return power_two_sided(size, eb / math.sqrt(k), dof=dof)
    v = decide(p, at(1.0), "the rescaled PDFs P(v/⟨v²⟩^½) collapse: ⟨|v|^m⟩/⟨v²⟩^(m/2) is the "
               "same at every N", f"the thesis' multi-scaling: slope m(ξ₂/2 − ξ_m/m) = {size:.3g} "
               f"for m = {m} (ξ₂/2 ≃ {XI2_2}, ξ_{m}/{m} ≃ {XI_M[m]})",
               f"slope of ln(⟨|v|^{m}⟩/⟨v²⟩^{m / 2:g}) against ln N: {b:.3g} ± {eb:.2g} "
               f"({abs(b) / eb:.1f}σ from a collapse"
               + (f", Student's t of {dof:.1f} degrees of freedom)" if dof else ")"),
               math.nan, feature=True, power_at=at)
    return v, m, fits


def slope_dof(x, e, dofs):
    """Welch–Satterthwaite degrees of freedom of a weighted line's slope whose points' errors
    come from few seeds (dofs: each point's, None where its error is not a scatter): None when
    every error is known"""
    w = 1.0 / np.asarray(e, float) ** 2
    c = w * (x - np.sum(w * x) / np.sum(w))
    part = (c / np.sum(c * (x - np.sum(w * x) / np.sum(w)))) ** 2 * np.asarray(e, float) ** 2
    nu = [d for d in dofs if d]
    if not nu:
        return None
    den = sum(v * v / d for v, d in zip(part, dofs) if d)
    return float(np.sum(part) ** 2 / den) if den > 0 else None


def c_vpdf(d, sw="ring"):
    runs = _runs(d, sw)
    raw = _table(d, sw)
    eps = eps_values(raw)[0]
    v, m, fits = vpdf_test(raw, eps)
    b, eb, size, n = fits[m][:4]
    dof = fits[m][6]
    v = _gate(v, runs)
    sizes = ", ".join(f"{x:g}" for x in n)

    def draw(fig):
        a1, a2 = fig.add_subplot(121), fig.add_subplot(122)
        for k, r in enumerate(sorted(runs, key=lambda q: q["particles"])):
            q = r["runs"][0]
            pth = os.path.join(q["adir"], "velocity.csv")
            if not os.path.exists(pth):
                continue
            h = _csv(pth)[0]
            s = math.sqrt(q["T_mean"])
            ok = h["P"] > 0
            a1.plot(h["v"][ok] / s, h["P"][ok] * s, ".", ms=2, color=f"C{k}",
                    label=f"N = {r['particles']:g}" + (" (seed 1)" if len(r["runs"]) > 1 else ""))
        if not a1.lines:
            a1.text(0.5, 0.5, "no velocity.csv of these runs in this folder", ha="center",
                    transform=a1.transAxes)
        _ax(a1, f"rescaled velocity PDFs, ε = {eps:g} (thesis Fig. 3.6a)", "v/⟨v²⟩^½",
            "⟨v²⟩^½ P(v)", False, True, 7)
        for k in XI_M:
            bk, ebk, sz, nk, yk, ek, _ = fits[k]
            a2.errorbar(nk, np.exp(yk - yk.mean()), 1.96 * ek * np.exp(yk - yk.mean()), fmt="o",
                        capsize=3, label=f"m = {k}: slope {bk:.3f} ± {1.96 * ebk:.3f}")
            nn = np.geomspace(nk.min(), nk.max(), 20)
            g = math.exp(np.mean(np.log(nk)))
            a2.plot(nn, (nn / g) ** sz, "--", color=a2.lines[-1].get_color() if a2.lines else None,
                    lw=0.8, label=f"thesis slope {sz:.3g}")
        a2.axhline(1, color="k", ls=":", label="a collapse")
        _ax(a2, f"⟨|v|^m⟩/⟨v²⟩^(m/2), each over its mean (tested: m = {m})", "N",
            "relative value", True, True, 7)
    return dict(measured=f"slope of ln(⟨|v|^{m}⟩/⟨v²⟩^{m / 2:g}) over ln N = {_ci(b, eb, dof)} (95 %) "
                f"over N = {sizes} at ε = {eps:g}; thesis {size:.3g}; m = {m} of "
                f"{', '.join(map(str, XI_M))} has the most power", verdict=v,
                chart=_chart(d, "v-pdf", draw, wide=True),
                values=dict(m=m, slope=b, slope_err=eb, thesis_slope=size))


"""Comparison charts of the Random Force Model analyses, used by gransim.charts.rfm:

  gh_bisection.csv (+ gh.csv)      G_h(R) of the 1D ring against the uniform multiplicative
                                   bisection (T.3.25 with T.3.36)              -> gh_bisection.png
  velocity.csv + velocity_post.csv (analysis folder) or
  hist_velocity.csv + hist_postcollision.csv (run folder)
                                   post-collision against overall P(v)         -> postcollision.png
  moments_vs_N.csv + exponents.csv (the analysis folder above the runs)
                                   <|v|^m>, <R^m> against N with xi_m, zeta_m  -> moments_vs_N.png

Every function returns the PNG path, or None after printing why the chart was skipped.
"""
import json
import math
import os

import numpy as np
import matplotlib.pyplot as plt

from .rfm import read_csv, save


def skip(what, why):
    print(f"skipped ({why}): {what}")
    return None


def _bisection_density(x, levels):
    """segment-length density of the uniform bisection after `levels` splits (T.3.36)"""
    if levels < 1:
        return np.full_like(x, np.nan)
    u = -np.log(x)
    return np.exp((levels - 1) * np.log(np.where(u > 0, u, np.nan)) - math.lgamma(levels))


def _log_err(y, e):
    """error bars that stay above zero on a log axis"""
    return np.vstack([np.minimum(e, 0.9 * y), e])


def _overlap_scale(csv_dir):
    """0.1 µm in units of L′: below it the 1D 'gaps' are mostly overlaps of touching disks (soft
    disks overlap by 0.1–1 µm in a contact, docs/rfm.md), or None"""
    try:
        with open(os.path.join(csv_dir, "rfm.json")) as f:
            lr = json.load(f).get("reduced_length")
        return 1e-7 / lr if lr and lr > 0 else None
    except (OSError, ValueError, TypeError):
        return None


def _levels(csv_dir, meta):
    """n of the bisection with 2^n segments: the gh_bisection.csv metadata, else log2 N"""
    if "levels" in meta:
        return int(round(meta["levels"])), int(round(meta.get("N", 2 ** meta["levels"])))
    try:
        with open(os.path.join(csv_dir, "rfm.json")) as f:
            info = json.load(f)
        if info.get("dimension") != 1:
            return None, None
        n_part = info["particles"]
        return int(round(math.log2(n_part))), int(n_part)
    except (OSError, KeyError, ValueError, TypeError):
        return None, None


def gh_bisection(csv_dir, out, bisection_csv=None):
    """G_1 of the ring beside the bisection density (thesis Fig. 3.16), and G_h, h = 2^j, beside
    the density after n − j splits: by the renormalisation T.3.25, G_h(R; N) = G_1(R; N/h), and
    G_1 of 2^(n−j) bisection boundaries is (−ln R)^(n−j−1)/(n−j−1)!."""
    src = os.path.join(csv_dir, "gh_bisection.csv")
    gh_src = os.path.join(csv_dir, "gh.csv")
    if not os.path.exists(src) and not os.path.exists(gh_src):
        return skip(src, "missing, not a 1D run")
    m, c = read_csv(src) if os.path.exists(src) else ({}, {})
    gm, g = read_csv(gh_src) if os.path.exists(gh_src) else ({}, {})
    if not c and not g:
        return skip(src, "no data")
    if not c:
        c = {"R": g["R"], "G1": g["G1"], "G1_err": g["G1_err"]}
    n, n_part = _levels(csv_dir, m)
    if n is None:
        return skip(src, "no levels / particle number to compare with")
    R = c["R"]
    if len(R) == 0 or not np.any(c["G1"] > 0):
        return skip(src, "G1 is empty")
    model = None
    if bisection_csv and os.path.exists(bisection_csv):
        bm, bc = read_csv(bisection_csv)
        model = (int(bm["levels"]), bc)

    fig, axs = plt.subplots(1, 2, figsize=(12, 4.6))
    # left: G_1 against the bisection and the uniform gas, log R (thesis Fig. 3.16)
    ax = axs[0]
    ok = c["G1"] > 0
    ax.errorbar(R[ok], c["G1"][ok], yerr=_log_err(c["G1"][ok], c["G1_err"][ok]), fmt="x", ms=4,
                color="k", elinewidth=0.5, label=f"1D RFM G₁(R), N = {n_part}")
    r_touch = _overlap_scale(csv_dir)
    if r_touch:
        for a in axs:
            if a is axs[0]:
                a.axvspan(R.min() / 2, r_touch, color="0.9", zorder=0,
                          label=f"R < {r_touch:.0e} L′: mostly touching disks (the 'gap' is their overlap)")
            else:
                a.axvspan(-math.log(r_touch), -math.log(R.min() / 2), color="0.9", zorder=0)
    pb = c["P_bisection"] if "P_bisection" in c else _bisection_density(R, n)
    ax.plot(R, pb, color="C3", lw=1.5, label=f"bisection (−ln R)^(n−1)/(n−1)!, n = {n} (T.3.36)")
    if "P_uniform" in c:
        pu = c["P_uniform"] > 1e-300
        ax.plot(R[pu], c["P_uniform"][pu], "--", color="C0", lw=1,
                label=f"{n_part} uniform points (elastic gas)")
    if model is not None:
        mc = model[1]
        mok = mc["G1"] > 0
        ax.plot(mc["x"][mok], mc["G1"][mok], "o", ms=3, mfc="none", color="C3",
                label=f"bisection model G₁ (gransim model bisection, n = {model[0]})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    top = np.nanmax(np.concatenate([c["G1"][ok], pb[np.isfinite(pb)]]))
    ax.set_ylim(max(1e-6, 1e-3 * c["G1"][ok].min()), 5 * top)
    ax.set_xlabel("R (units of L′)")
    ax.set_ylabel("G₁(R) (1/L′)")
    ax.set_title("nearest-neighbour gaps vs uniform bisection (Fig. 3.16)")
    ax.legend(fontsize=7, loc="lower left")

    # right: G_h against −ln R, each with the bisection density after n − log2 h splits
    ax = axs[1]
    hs = sorted(int(k[1:]) for k in g if k.startswith("G") and not k.endswith("_err")) if g else [1]
    lo_all, hi_all = [], []
    for i, h in enumerate(hs):
        col = f"C{i}"
        gh = g["G%d" % h] if g else c["G1"]
        rr = g["R"] if g else R
        okh = (gh > 0) & (rr < 1)
        if not okh.any():
            continue
        lo_all.append(gh[okh].min())
        hi_all.append(gh[okh].max())
        ax.plot(-np.log(rr[okh]), gh[okh], ".", ms=4, color=col, label=f"RFM G_{h}")
        j = int(round(math.log2(h)))
        if 2 ** j == h and n - j >= 1:
            xs = np.logspace(np.log10(-np.log(rr[rr < 1].max())), np.log10(-np.log(rr.min())), 200)
            ax.plot(xs, _bisection_density(np.exp(-xs), n - j), "-", color=col, lw=1.2,
                    label=f"bisection, n − {j} = {n - j} levels" if j else f"bisection, n = {n} levels")
    if model is not None and "G2" in model[1]:
        mc = model[1]
        mok = (mc["G2"] > 0) & (mc["x"] < 1)
        ax.plot(-np.log(mc["x"][mok]), mc["G2"][mok], "+", ms=5, color="C1",
                label=f"bisection model G₂ (n = {model[0]})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    if lo_all:
        ax.set_ylim(max(1e-6, 0.3 * min(lo_all)), 5 * max(hi_all))
    ax.set_xlabel("−ln R (R in units of L′)")
    ax.set_ylabel("G_h(R) (1/L′)")
    ax.set_title("h-th neighbours vs bisection with log₂h fewer levels (T.3.25)")
    ax.legend(fontsize=7, ncol=2, loc="upper left")
    return save(fig, out, "gh_bisection.png")


def _velocity_pair(csv_dir):
    """(overall, post-collision) as (meta, columns with 'v'), from an analysis folder
    (velocity.csv + velocity_post.csv, with tail fits) or from a run folder (hist_*.csv)"""
    for a, b in (("velocity.csv", "velocity_post.csv"), ("hist_velocity.csv", "hist_postcollision.csv")):
        pa, pb = os.path.join(csv_dir, a), os.path.join(csv_dir, b)
        if os.path.exists(pa) and os.path.exists(pb):
            out = []
            for p in (pa, pb):
                m, c = read_csv(p)
                if "v" not in c and "x" in c:
                    c["v"] = c["x"]
                out.append((m, c))
            return out, (a, b)
    return None, None


def _rms(c):
    w = c["count"]
    return math.sqrt((w * c["v"] ** 2).sum() / w.sum()) if w.sum() > 0 else float("nan")


def postcollision(csv_dir, out):
    pair, names = _velocity_pair(csv_dir)
    if pair is None:
        return skip(os.path.join(csv_dir, "velocity_post.csv"),
                    "no post-collision histogram (velocity_post.csv or hist_postcollision.csv)")
    (ma, a), (mb, b) = pair
    if not (a["count"].sum() > 0 and b["count"].sum() > 0):
        return skip(os.path.join(csv_dir, names[1]), "an empty histogram")
    sa, sb = _rms(a), _rms(b)
    fig, axs = plt.subplots(1, 2, figsize=(12, 4.6))
    for ax, scaled in zip(axs, (False, True)):
        lo_all, hi_all, hi_v = [], [], 0.0
        for (m, c, s, col, what, n) in ((ma, a, sa, "k", "all velocities", a["count"].sum()),
                                        (mb, b, sb, "C3", "post-collision", b["count"].sum())):
            ok = c["count"] > 0
            x = c["v"][ok] / s if scaled else c["v"][ok]
            y = c["P"][ok] * s if scaled else c["P"][ok]
            e = c["P_err"][ok] * s if scaled else c["P_err"][ok]
            ax.errorbar(x, y, yerr=e, fmt=".", ms=2.5, color=col, elinewidth=0.4,
                        label=f"{what}: v_rms = {s:.3g} m/s, {n:.3g} samples")
            lo_all.append(y.min())
            hi_all.append(y.max())
            hi_v = max(hi_v, np.abs(x).max())
            if "P_tail" in c and np.isfinite(c["P_tail"]).any():
                t = np.isfinite(c["P_tail"])
                for side in (c["v"] < 0, c["v"] > 0):
                    sel = t & side
                    if sel.any():
                        xs = c["v"][sel] / s if scaled else c["v"][sel]
                        ys = c["P_tail"][sel] * s if scaled else c["P_tail"][sel]
                        ax.plot(xs, ys, "-", color="C1" if col == "k" else "C4", lw=2.2, alpha=0.8,
                                label=(f"tail fit of {what}: α = {m['alpha_best']:.2f}"
                                       if side[-1] and "alpha_best" in m else None))
        # a Gaussian of the overall variance (per component)
        xs = np.linspace(-hi_v, hi_v, 400)
        if scaled:
            ax.plot(xs, np.exp(-0.5 * xs ** 2) / math.sqrt(2 * math.pi), "--", color="0.5", lw=1,
                    label="unit Gaussian")
        else:
            ax.plot(xs, np.exp(-0.5 * (xs / sa) ** 2) / (sa * math.sqrt(2 * math.pi)), "--",
                    color="0.5", lw=1, label="Gaussian of the overall v_rms")
        ax.set_yscale("log")
        ax.set_ylim(0.3 * min(lo_all), 60 * max(hi_all))  # room for the legend above the peak
        ax.set_xlim(-1.05 * hi_v, 1.05 * hi_v)
        ax.legend(fontsize=7, loc="upper left", framealpha=0.9)
    axs[0].set_xlabel("v (m/s), one component")
    axs[0].set_ylabel("P(v) (s/m)")
    axs[0].set_title("post-collision vs overall velocity distribution")
    axs[1].set_xlabel("v / v_rms (each distribution by its own v_rms)")
    axs[1].set_ylabel("v_rms · P(v)")
    axs[1].set_title("the same, scaled to unit variance (shape)")
    return save(fig, out, "postcollision.png")


def moments_vs_n(csv_dir, out):
    """<|v|^m> (and 1D <R^m>) against N, relative to the smallest N, with the fits
    A N^(−ξ_m) of exponents.csv (T.3.13, T.3.20); one row of panels per (dimension, ε) group with
    two or more system sizes"""
    src = os.path.join(csv_dir, "moments_vs_N.csv")
    if not os.path.exists(src):
        return skip(src, "missing")
    _, c = read_csv(src)
    if len(c.get("N", [])) == 0:
        return skip(src, "no rows")
    ex = {}
    pe = os.path.join(csv_dir, "exponents.csv")
    if os.path.exists(pe):
        _, e = read_csv(pe)
        for i in range(len(e.get("m", []))):
            key = (int(e["dimension"][i]), e["eps_n"][i], e["eps_t"][i], int(e["quantity"][i]), int(e["m"][i]))
            ex[key] = (e["exponent"][i], e["exponent_err"][i], e["amplitude"][i], e["chi2_r"][i])
    groups = sorted({(int(d), en, et) for d, en, et in zip(c["dimension"], c["eps_n"], c["eps_t"])})
    rows = []
    for grp in groups:
        sel = (c["dimension"] == grp[0]) & (c["eps_n"] == grp[1]) & (c["eps_t"] == grp[2])
        if len(np.unique(c["N"][sel])) >= 2:
            rows.append((grp, sel))
        else:
            print(f"moments_vs_N: {grp[0]}D, ε_n = {grp[1]:g}, ε_t = {grp[2]:g} has one system size "
                  f"(N = {c['N'][sel][0]:.0f}); no exponent fit to draw")
    if not rows:
        return skip(src, "no group of runs with two or more system sizes")
    ms = [1, 2, 3, 4, 6, 8, 12]
    fig = plt.figure(figsize=(15, 4.4 * len(rows)))
    for r, (grp, sel) in enumerate(rows):
        dim = grp[0]
        quantities = [(0, "v_moment", "v_err", "⟨|v|^m⟩", "ξ_m")]
        if dim == 1 and np.isfinite(c["R_moment"][sel]).any():
            quantities.append((1, "R_moment", "R_err", "⟨R^m⟩", "ζ_m"))
        tag = f"{dim}D, ε_n = {grp[1]:g}" + (f", ε_t = {grp[2]:g}" if dim == 2 else "")
        for qi, (q, col, err, name, xi) in enumerate(quantities):
            ax = fig.add_subplot(len(rows), 3, 3 * r + 1 + qi)
            for k, m in enumerate(ms):
                s = sel & (c["m"] == m) & np.isfinite(c[col]) & (c[col] > 0)
                if s.sum() < 1:
                    continue
                order = np.argsort(c["N"][s])
                N, y, ye = c["N"][s][order], c[col][s][order], c[err][s][order]
                y0 = y[0]
                ax.errorbar(N, y / y0, yerr=ye / y0, fmt="o", ms=4, color=f"C{k}", elinewidth=0.6,
                            label=f"m = {m}")
                f = ex.get((dim, grp[1], grp[2], q, m))
                if f is not None and np.isfinite(f[0]):
                    ns = np.geomspace(N.min() / 1.1, N.max() * 1.1, 20)
                    ax.plot(ns, f[2] * ns ** (-f[0]) / y0, "-", color=f"C{k}", lw=1,
                            label=f"{xi[0]}_{m} = {f[0]:.3f} ± {f[1]:.3f}")
            ax.set_xscale("log")
            ax.set_yscale("log")
            sizes = np.unique(c["N"][sel])
            ax.set_xticks(sizes)
            ax.set_xticklabels([f"{v:.0f}" for v in sizes])
            ax.minorticks_off()
            ax.set_xlabel("N (particles)")
            unit = "m/s" if q == 0 else "units of L′"
            ax.set_ylabel(f"{name} / {name} at N = {sizes[0]:.0f} (dimensionless)")
            ax.set_title(f"{tag}: {name} ({unit}) ∝ N^(−{xi}), lines: fits")
            ax.legend(fontsize=6.5, ncol=2)
        ax = fig.add_subplot(len(rows), 3, 3 * r + 1 + len(quantities))
        drawn = False
        for q, _, _, name, xi in quantities:
            pts = [(m,) + ex[(dim, grp[1], grp[2], q, m)] for m in range(1, 13)
                   if (dim, grp[1], grp[2], q, m) in ex]
            if not pts:
                continue
            p = np.array(pts)
            ax.errorbar(p[:, 0], p[:, 1], yerr=p[:, 2], fmt="o-" if q == 0 else "s-", ms=4, lw=0.8,
                        label=f"{xi} of {name}")
            drawn = True
        mm = np.arange(1, 13)
        if dim == 1:
            ax.plot(mm, mm / 3.0, ":", color="0.4", label="ξ_m = m/3 (homogeneous mean field)")
            if len(quantities) > 1:
                ax.plot(mm, np.log2(1 + mm), "--", color="C3", lw=0.8,
                        label="ζ_m = log₂(1+m) (uniform bisection, T.3.38)")
                ax.plot(mm, mm * 1.0, "--", color="0.6", lw=0.8, label="ζ_m = m (uniform gaps)")
        if not drawn:
            ax.text(0.5, 0.5, "exponents.csv has no fit for this group", ha="center",
                    transform=ax.transAxes)
        ax.set_xlabel("moment order m")
        ax.set_ylabel("exponent (dimensionless)")
        ax.set_title(f"{tag}: scaling exponents, {int(len(np.unique(c['N'][sel])))} sizes")
        ax.legend(fontsize=7)
    return save(fig, out, "moments_vs_N.png")

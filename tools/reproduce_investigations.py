#!/usr/bin/env python3
"""The tapping study's open questions, decided from the runs kept in
docs/reproduction/investigations/: is the weak-tap steady state (g_p = 2) history-dependent, does
rotating g's φ̄(f) reach the paper's high-frequency level beyond 2 Hz, and do one long run's test
columns obey the paper's halves bounds. Prints every number docs/reproduction/README.md quotes
and draws the charts beside the series.

  tools/reproduce_investigations.py [FOLDER]        (default docs/reproduction/investigations)

FOLDER/runs.csv names each run (name, protocol, control, start, taps, note) and FOLDER/series/
holds each run's per-tap φ, φ_left and φ_right (the runs' taps.csv columns, `gransim run` output).
Errors are batch means with Student's t (python/gransim/reproduce/batch.py), the rule the reports
use; a steady part starts at MSER-5's cut."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from gransim.reproduce.batch import batch_err  # noqa: E402
from gransim.reproduce.verdicts import P_REJECT, below_bound, t_of, t_sf2  # noqa: E402

HIGH_F_LEVEL = 0.821  # the paper's φ̄ at high rotation frequency (Fig. 6a), printed to 3 decimals
HALVES_MEAN, HALVES_SIGMA = 1e-4, 0.01  # the paper's bounds on the test square's columns


def mser(x, batch=5):
    """MSER-5: the cut (in taps, a multiple of batch) that minimises the squared standard error
    of the mean of what is left, searched over the first half"""
    n = len(x) // batch
    y = np.asarray(x[:n * batch], float).reshape(n, batch).mean(axis=1)
    best, cut = math.inf, 0
    for d in range(n // 2 + 1):
        rest = y[d:]
        s = float(np.var(rest)) / len(rest)  # the MSER statistic
        if s < best:
            best, cut = s, d
    return cut * batch


def compaction_many(Y):
    """least squares φ_n = φ_∞ − A·e^(−n/τ) for each row of Y, τ over a log grid from 0.5 to
    five times the series: arrays (φ_∞, A, τ), one entry a row"""
    Y = np.atleast_2d(np.asarray(Y, float))
    n = np.arange(Y.shape[1], dtype=float)
    taus = np.geomspace(0.5, 5 * Y.shape[1], 160)
    X = np.stack([np.stack([np.ones_like(n), -np.exp(-n / t)], axis=1) for t in taus])
    coef = np.linalg.pinv(X) @ Y.T  # (grid, 2, rows)
    sse = ((X @ coef - Y.T[None]) ** 2).sum(axis=1)  # (grid, rows)
    k = sse.argmin(axis=0)
    rows = np.arange(Y.shape[0])
    return coef[k, 0, rows], coef[k, 1, rows], taus[k]


def compaction(phi):
    """the compaction fit of one run: dict(inf, A, tau, curve, a, sd), the curve the fit less
    its plateau, a and sd the residuals' lag-one correlation and standard deviation"""
    phi = np.asarray(phi, float)
    inf, a, tau = (float(v[0]) for v in compaction_many(phi))
    curve = -a * np.exp(-np.arange(len(phi)) / tau)
    res = phi - inf - curve
    r1 = float(np.corrcoef(res[:-1], res[1:])[0, 1])
    return dict(inf=inf, A=a, tau=tau, curve=curve, a=min(max(r1, 0.0), 0.95),
                sd=float(np.std(res, ddof=3)))


def load(folder):
    runs = {}
    with open(os.path.join(folder, "runs.csv")) as f:
        for r in csv.DictReader(f):
            path = os.path.join(folder, "series", r["name"] + ".csv")
            if not os.path.exists(path):
                continue
            with open(path) as g:
                rows = list(csv.DictReader(g))
            if len(rows) < 20:  # a run only just started: nothing to say yet
                continue
            r["phi"] = np.array([float(x["phi"]) for x in rows])
            r["left"] = np.array([float(x["phi_left"]) for x in rows])
            r["right"] = np.array([float(x["phi_right"]) for x in rows])
            runs[r["name"]] = r
    return runs


def standard_summary():
    """φ̄ and its error of each run of the standard tapping report, by protocol and control"""
    path = os.path.join(ROOT, "docs", "reproduction", "tapping-standard", "analysis",
                        "summary.csv")
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return {(r["protocol"], float(r["control"])): (float(r["phi_mean"]), float(r["phi_err"]))
                for r in csv.DictReader(f)}


def steady(phi):
    cut = mser(phi)
    m, e, dof = batch_err(phi[cut:])
    return cut, m, e, dof


def weak_tap(runs, folder=None):
    """g_p = 2 from the loose settled pile and from the pile annealed by decreasing g_p: the
    difference of the two steady means (a chart in folder unless None)"""
    print("## g_p = 2 from two starts")
    chain = [r for r in runs.values() if r["start"].startswith("anneal (")]
    std = standard_summary()
    for r in chain:
        p = r["phi"]
        ref = std.get((r["protocol"], float(r["control"])))
        print(f"  anneal {r['protocol']} {r['control']}: {len(p)} taps, φ from {p[0]:.4f} to "
              f"{p[-1]:.4f}, last 10 taps {p[-10:].mean():.4f} ± "
              f"{p[-10:].std(ddof=1) / math.sqrt(10):.4f}"
              + (f"; the standard report's steady φ̄ here {ref[0]:.4f} ± {ref[1]:.4f}" if ref else ""))
    pair = [r for r in runs.values() if r["protocol"] == "negative_g" and r["control"] == "2"]
    out = {}
    fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=110) if folder else (None, None)
    found = {}
    for r in pair:
        p = r["phi"]
        cut, m, e, dof = steady(p)
        fit = compaction(p)
        found[r["start"]] = fit
        h = (len(p) - cut) // 2  # drift: the steady part's second half against its first
        (m1, e1, d1), (m2, e2, d2) = batch_err(p[cut:cut + h]), batch_err(p[cut + h:])
        drift = f"{m2 - m1:+.5f} ± {math.hypot(e1, e2):.5f}" if d1 and d2 else "too short"
        print(f"  {r['name']} ({r['start']} start): {len(p)} taps, first {p[0]:.4f}; MSER cut "
              f"{cut}, mean after it {m:.5f} ± {e:.5f} ({dof} dof), drift (its second half − "
              f"first) {drift}; compaction fit τ {fit['tau']:.1f} taps, A {fit['A']:.4f}, "
              + (f"φ_∞ {fit['inf']:.5f}" if fit["tau"] < len(p) / 3 else
                 "no plateau within the run") + f"; residuals sd {fit['sd']:.5f}, lag-one "
              f"correlation {fit['a']:.2f}")
        if ax:
            c = ax.plot(np.arange(len(p)), p, ".", ms=3, label=f"{r['start']} start")[0].get_color()
            ax.plot(np.arange(len(p)), fit["inf"] + fit["curve"], lw=1, color=c)
            ax.axvline(cut, color=c, ls=":", lw=0.8)
    if len(found) == 2:
        # at the same taps: the loose run may still be compacting, so a difference here is the
        # two histories' φ at equal tap counts, not yet two steady states
        p1, p2 = pair[0]["phi"], pair[1]["phi"]
        n = min(len(p1), len(p2))
        w = slice(n - n // 3, n)
        (m1, e1, d1), (m2, e2, d2) = batch_err(p1[w]), batch_err(p2[w])
        d, de = m2 - m1, math.hypot(e1, e2)
        dof = de ** 4 / (e1 ** 4 / max(d1, 1) + e2 ** 4 / max(d2, 1))  # Welch–Satterthwaite
        pv = t_sf2(abs(d / de), dof)
        out = dict(difference=d, err=de, dof=dof, p=pv, taps=(w.start, n))
        print(f"  at taps {w.start}–{n - 1}: {pair[1]['name']} − {pair[0]['name']} = {d:+.5f} ± "
              f"{de:.5f} (t = {d / de:+.2f}, {dof:.0f} dof, p = {pv:.2g})")
        ref = std.get(("negative_g", 2.0))
        if ref:
            print(f"  the standard report's g_p = 2 (250 taps from the loose pile, after its cut): "
                  f"φ̄ {ref[0]:.5f} ± {ref[1]:.5f}")
    if ax:
        ax.set_xlabel("tap")
        ax.set_ylabel("φ")
        ax.set_title("g_p = 2 from a loose and an annealed pile (lines: compaction fits; "
                     "dotted: MSER cuts)", fontsize=9)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "weak_tap.png"))
        plt.close(fig)
    return out


def high_f(runs, folder):
    """rotating g beyond the reports' 2 Hz"""
    rot = sorted((r for r in runs.values() if r["protocol"] == "rotating_g"
                  and r["start"] == "settled"), key=lambda r: float(r["control"]))
    if not rot:
        return []
    print("## rotating g beyond 2 Hz")
    std = sorted((k[1], v) for k, v in standard_summary().items() if k[0] == "rotating_g")
    for f, (m, e) in std:
        print(f"  standard report, f = {f:g} Hz: φ̄ {m:.5f} ± {e:.5f}")
    xs, ms, es, dofs = [], [], [], []
    for r in rot:
        cut, m, e, dof = steady(r["phi"][1:])  # tap 0 is the settled pile, before any turn
        xs.append(float(r["control"]))
        ms.append(m)
        es.append(e)
        dofs.append(dof)
        z = (m - HIGH_F_LEVEL) / math.hypot(e, 0.0005)
        print(f"  f = {r['control']} Hz: taps 1–{len(r['phi']) - 1} (tap 0 the settled pile, "
              f"{r['phi'][0]:.4f}), cut {cut}, φ̄ {m:.5f} ± {e:.5f} "
              f"({dof} dof); against {HIGH_F_LEVEL} ± 0.0005: {z:+.1f}σ")
    if std:
        f, (m, e) = std[-1]
        d, de = ms[0] - m, math.hypot(es[0], e)
        print(f"  {f:g} (standard) → {xs[0]:g} Hz: Δφ̄ {d:+.5f} ± {de:.5f} ({d / de:+.1f}σ)")
    for i in range(1, len(xs)):
        d, de = ms[i] - ms[i - 1], math.hypot(es[i], es[i - 1])
        print(f"  {xs[i - 1]:g} → {xs[i]:g} Hz: Δφ̄ {d:+.5f} ± {de:.5f} ({d / de:+.1f}σ)")
    fig, ax = plt.subplots(figsize=(6.4, 3.6), dpi=110)
    if std:
        ax.errorbar([f for f, _ in std], [v[0] for _, v in std],
                    yerr=[1.96 * v[1] for _, v in std], fmt="s", capsize=3, color="0.5",
                    label="standard report (200 taps), 95 %")
    ax.errorbar(xs, ms, yerr=1.96 * np.array(es), fmt="o", capsize=3,
                label=f"these runs ({len(rot[0]['phi']) - 1} taps), 95 %")
    ax.axhline(rot[0]["phi"][0], color="0.3", ls=":", lw=1, label="the settled pile (tap 0)")
    ax.axhspan(HIGH_F_LEVEL - 0.0005, HIGH_F_LEVEL + 0.0005, color="tab:orange", alpha=0.3,
               label="paper's high-f level 0.821")
    ax.set_xlabel("f (Hz)")
    ax.set_ylabel("φ̄")
    ax.legend(fontsize=8, loc="center right")
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "high_f.png"))
    plt.close(fig)
    return list(zip(xs, ms, es, dofs))


def halves_chart(r, cut, folder):
    """the left column's relative excess over the square: 50-tap means, and the whole mean with
    its one-sided 99.75 % limits as the run grew, against the paper's bound"""
    p, pl = r["phi"][1 + cut:], r["left"][1 + cut:]
    d = (pl - p) / p
    fig, (a, b) = plt.subplots(1, 2, figsize=(9.6, 3.6), dpi=110)
    m = 50
    k = len(d) // m
    a.plot(cut + 1 + np.arange(len(d)), 1e3 * d, ".", ms=1.5, color="0.7", label="each tap")
    a.plot(cut + 1 + m * (np.arange(k) + 0.5), 1e3 * d[:k * m].reshape(k, m).mean(axis=1), "o-",
           ms=3, label=f"{m}-tap means")
    ns, ms_, lo, hi = [], [], [], []
    for n in range(100, len(d) + 1, 50):
        mean, e, dof = batch_err(d[:n])
        t = t_of(P_REJECT / 2, dof) * e  # below_bound's limit: 1 % over two columns, two-sided
        ns.append(cut + n)
        ms_.append(1e3 * mean)
        lo.append(1e3 * (mean - t))
        hi.append(1e3 * (mean + t))
    for ax in (a, b):
        ax.axhspan(-1e3 * HALVES_MEAN, 1e3 * HALVES_MEAN, color="tab:orange", alpha=0.4,
                   label="the paper's bound |Δφ|/φ < 10⁻⁴")
        ax.axhline(0, color="0.3", lw=0.6)
        ax.set_xlabel("tap")
    b.fill_between(ns, lo, hi, alpha=0.3,
                   label="one-sided 99.75 % limits (Student's t, batch means)")
    b.plot(ns, ms_, "-", label="mean of the taps so far")
    a.set_ylabel("(φ_left − φ) / φ  (10⁻³)")
    b.set_ylabel("mean (φ_left − φ) / φ  (10⁻³)")
    a.set_title(f"{r['name']}: the left column, tap by tap", fontsize=9)
    b.set_title("its mean as the run grew", fontsize=9)
    a.legend(fontsize=7, loc="lower right")
    b.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(os.path.join(folder, "halves.png"))
    plt.close(fig)


def halves(runs, folder=None):
    """one long run's columns against the whole test square (a chart in folder unless None)"""
    long = [r for r in runs.values() if r["start"] == "long"]
    out = {}
    for r in long:
        p, pl, pr = r["phi"][1:], r["left"][1:], r["right"][1:]  # tap 0: the settled pile
        cut = mser(p)
        print(f"## halves, {r['name']}: {len(p)} of {r['taps']} taps, cut {cut}")
        if folder:
            halves_chart(r, cut, folder)
        for side, c in (("left", pl), ("right", pr)):
            m, e, dof = batch_err(((c - p) / p)[cut:])
            v = below_bound(abs(m), e, HALVES_MEAN, dof=dof, family=2, folded=True)
            out[(r["name"], side)] = v
            print(f"  relative difference {side} − whole: {m:+.2e} ± {e:.1e} ({dof} dof): "
                  f"{v.verdict} (power {v.power:.2f}); {v.reason}")
        def ratio(a, b, c):
            return 0.5 * (np.std(b, ddof=1) + np.std(c, ddof=1)) / np.std(a, ddof=1) / math.sqrt(2)

        m, e, dof = batch_err([p[cut:], pl[cut:], pr[cut:]], ratio)
        v = below_bound(abs(m - 1), e, HALVES_SIGMA, dof=dof, folded=True)
        out[(r["name"], "sigma")] = v
        print(f"  σ ratio / √2: {m:.4f} ± {e:.4f} ({dof} dof): {v.verdict} (power {v.power:.2f}); "
              f"{v.reason}")
    return out


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "docs", "reproduction",
                                                                 "investigations")
    if not os.path.isfile(os.path.join(folder, "runs.csv")):
        sys.exit(f"reproduce_investigations: {os.path.join(folder, 'runs.csv')}: no such file "
                 "(FOLDER must hold runs.csv and series/)")
    runs = load(folder)
    weak_tap(runs, folder)
    high_f(runs, folder)
    halves(runs, folder)


if __name__ == "__main__":
    main()

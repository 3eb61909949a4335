#!/usr/bin/env python3
"""The Random Force Model's open questions at the thesis' φ = 0.530, ε = 0.1, decided from the
runs kept in docs/reproduction/investigations/rfm/: does the free-path dimension (§4.3.3, eq.
4.25) depend on the box or on the time sampled; does g(R)'s large-R level (Fig. 4.7's "constant
fit of 0.98") depend on where it is read or on the time sampled; and how much of the crossover
fit's v_r and v_c/v_r (T.5.32, Table 5.3) is set by the fit's weights and range, which the
thesis does not state. Prints every number docs/reproduction/README.md quotes and draws the
charts beside the tables.

  tools/reproduce_investigations_rfm.py [FOLDER]
      print and draw (FOLDER: docs/reproduction/investigations/rfm)
  tools/reproduce_investigations_rfm.py --collect FOLDER NAME=RUN_DIR:ANALYSIS_DIR ...
      keep the tables of those runs (ANALYSIS_DIR: what `gransim analyze` wrote for RUN_DIR)

FOLDER/runs.csv names each run (name, L in m, N, the window sampled in s, seed, how it was made);
FOLDER/tables/NAME/ holds what `gransim analyze` wrote for it (the freepath and gr tables with
their fits, S(k) by its fit only, the velocity histogram where the run has one) and
gr_half.csv, g(R) up to L/2 from the run's last snapshot, which the run's own g(R) (to L/4) does
not reach. Seeds' spread is the error where a box has
several seeds."""
import csv
import gzip
import json
import math
import os
import shutil
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "python"))
from gransim.reproduce.rfm_fluid import CROSSOVER, fit_p0, p0  # noqa: E402

THESIS_DF, THESIS_C = 1.61, 121.0  # §4.3.3 at L = 0.6 m; C from §5.3.3 for φ = 0.530
THESIS_LEVEL = 0.98  # Fig. 4.7, L = 0.4 m


def _open(path):
    return gzip.open(path, "rt") if path.endswith(".gz") else open(path)


def table(path):
    """columns of a CSV (plain or .gz) as float arrays"""
    for p in (path, path + ".gz"):
        if os.path.exists(p):
            with _open(p) as f:
                rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
            out = {}
            for i, k in enumerate(rows[0]):
                try:
                    out[k] = np.array([float(r[i]) for r in rows[1:]])
                except ValueError:  # a text column (a state's species)
                    continue
            return out
    raise FileNotFoundError(path)


def meta(path):
    for p in (path, path + ".gz"):
        if os.path.exists(p):
            with _open(p) as f:
                return json.load(f)
    raise FileNotFoundError(path)


def snapshot_gr(state_csv, box, bins=200):
    """g(R) on [0, L/2) of one snapshot, minimum image, normalised by N(N−1)/2 pairs"""
    s = table(state_csv)
    x, y = s["x"] % box, s["y"] % box
    n = len(x)
    edges = np.linspace(0.0, box / 2, bins + 1)
    pairs = np.zeros(bins)
    for i in range(0, n - 1, 400):
        dx = x[i:i + 400, None] - x[None, :]
        dy = y[i:i + 400, None] - y[None, :]
        dx -= box * np.round(dx / box)
        dy -= box * np.round(dy / box)
        r = np.sqrt(dx * dx + dy * dy)
        keep = np.arange(i, min(i + 400, n))[:, None] < np.arange(n)[None, :]  # each pair once
        pairs += np.histogram(r[keep], edges)[0]
    shell = math.pi * (edges[1:] ** 2 - edges[:-1] ** 2)
    g = pairs / (n * (n - 1) / 2 * shell / box ** 2)
    return 0.5 * (edges[1:] + edges[:-1]), g, pairs


def collect(folder, specs):
    for spec in specs:
        name, dirs = spec.split("=", 1)
        run, analysis = dirs.split(":", 1)
        out = os.path.join(folder, "tables", name)
        os.makedirs(out, exist_ok=True)
        # S(k) enters by its fit alone (sk.json); its table is large
        for base, ext in (("freepath", ".csv"), ("freepath", ".json"), ("gr", ".csv"),
                          ("gr", ".json"), ("sk", ".json"), ("velocity", ".csv")):
            src = os.path.join(analysis, base + ext)
            if os.path.exists(src):
                with open(src, "rb") as f, open(os.path.join(out, base + ext + ".gz"), "wb") as raw, \
                        gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as g:
                    shutil.copyfileobj(f, g)
        with open(os.path.join(run, "rfm.json")) as f:
            info = json.load(f)
        box = float(info["box"])
        r, g, pairs = snapshot_gr(os.path.join(run, "state.csv"), box)
        text = "R,g,pairs\n" + "".join(f"{a:.6g},{b:.8g},{int(c)}\n" for a, b, c in zip(r, g, pairs))
        with open(os.path.join(out, "gr_half.csv.gz"), "wb") as raw, \
                gzip.GzipFile(fileobj=raw, mode="wb", mtime=0) as f:
            f.write(text.encode())
        print(f"kept {name} in {out}")


def runs_of(folder):
    with open(os.path.join(folder, "runs.csv")) as f:
        return list(csv.DictReader(f))


def tail_refit(fp, d_f):
    """C and χ²_r of T.4.25 with D_f held, on the analysis' window (A₀ and C free: a weighted line
    of ln P − (D_f − 2) ln l against l^(D_f − 1))"""
    c, m = fp
    w = (c["l"] >= m["l_fit_min"] * (1 - 1e-9)) & (c["count"] >= 10)
    l, p, s = c["l"][w], c["P"][w], 1.0 / np.sqrt(c["count"][w])
    y = np.log(p) - (d_f - 2.0) * np.log(l)
    x = l ** (d_f - 1.0)
    a = np.vstack([np.ones_like(x), x]).T / s[:, None]
    coef = np.linalg.lstsq(a, y / s, rcond=None)[0]
    chi2 = float(np.sum(((y - coef[0] - coef[1] * x) / s) ** 2))
    return -coef[1], chi2 / (len(l) - 2)


def level(gr, lo, hi):
    w = (gr["R"] >= lo) & (gr["R"] < hi)
    if "g_err" in gr:
        wt = 1.0 / gr["g_err"][w] ** 2
        return float(np.sum(gr["g"][w] * wt) / np.sum(wt))
    return float(np.sum(gr["g"][w] * gr["R"][w]) / np.sum(gr["R"][w]))  # pairs over expected


def excess(gr, box, n, hi):
    """neighbours beyond the mean density within R < hi: ∫ n (g − 1) 2πR dR"""
    w = gr["R"] < hi
    dr = np.gradient(gr["R"])
    return float(np.sum(n / box ** 2 * (gr["g"][w] - 1) * 2 * math.pi * gr["R"][w] * dr[w]))


def report(folder):
    rows = []
    for r in runs_of(folder):
        t = os.path.join(folder, "tables", r["name"])
        fp = (table(os.path.join(t, "freepath.csv")), meta(os.path.join(t, "freepath.json")))
        sk = meta(os.path.join(t, "sk.json"))
        gr, half = table(os.path.join(t, "gr.csv")), table(os.path.join(t, "gr_half.csv"))
        box, n = float(r["L"]), int(r["N"])
        c161, chi161 = tail_refit(fp, THESIS_DF)
        rows.append(dict(r, box=box, n=n, fp=fp[1], sk=sk, c161=c161, chi161=chi161,
                         lv=level(gr, box / 8, box / 4), half=level(half, box / 4, box / 2),
                         ex=excess(gr, box, n, box / 4), fpc=fp[0]))
    print("run | L (m) | window (s) | S(k) D_f | free-path D_f (tail) | χ²_r | l from (mm) | "
          "C at D_f = 1.61 (χ²_r) | g level [L/8, L/4) | snapshot g [L/4, L/2) | excess within L/4")
    for q in rows:
        print(f"{q['name']} | {q['box']:g} | {q['window']} | {q['sk']['D_f']:.3f} ± "
              f"{q['sk']['D_f_err']:.3f} | {q['fp']['D_f']:.3f} ± {q['fp']['D_f_err']:.3f} | "
              f"{q['fp']['chi2_r']:.2f} | {q['fp']['l_fit_min'] * 1e3:.2f} | {q['c161']:.0f} "
              f"({q['chi161']:.1f}) | {q['lv']:.5f} | {q['half']:.5f} | {q['ex']:.1f}")
    print()
    for box in sorted({q["box"] for q in rows}):
        seeds = [q for q in rows if q["box"] == box and q["window"] == first_window(rows, box)]
        if len(seeds) < 2:
            continue
        v = np.array([q["fp"]["D_f"] for q in seeds])
        lv = np.array([q["lv"] for q in seeds])
        half = np.array([q["half"] for q in seeds])
        print(f"L = {box:g} m, {len(seeds)} seeds ({seeds[0]['window']} s): free-path D_f "
              f"{v.mean():.3f} ± {t95(len(v)) * v.std(ddof=1) / math.sqrt(len(v)):.3f} (95 %); "
              f"g level {lv.mean():.5f}, snapshot level to L/2 {half.mean():.5f}")
    # the level a sum rule allows: ∫ n (g − 1) dA = −1 over the box, so a level g∞ below one over
    # the box outside L/4 needs an excess of (1 − g∞)·n·(L² − π(L/4)²) within L/4
    at04 = [q for q in rows if abs(q["box"] - 0.4) < 1e-9]
    if at04:
        n, box = at04[0]["n"], 0.4
        need = (1 - THESIS_LEVEL) * n / box ** 2 * (box ** 2 - math.pi * (box / 4) ** 2)
        have = ", ".join(f"{q['ex']:.1f}" for q in at04)
        print(f"a level of {THESIS_LEVEL} at L = 0.4 m needs ≈ {need:.0f} excess neighbours within "
              f"L/4; the runs have {have}")
    draw(folder, rows)
    crossover(folder, rows)


# the fit's choices the thesis does not state: each bin's ln P weighted by its Poisson error (the
# report's fit, the likelihood's), or every bin alike (a fit drawn on the log plot); the bins
# taken, by the counts they hold
WEIGHTS = ("Poisson", "equal")
MIN_COUNTS = (1, 10, 100, 1000)


def crossover_choices(c):
    """T.5.32 at α = 1 fitted to a velocity histogram under each weighting and each least count:
    a list of dicts (weights, min_count, decades of P taken, v_r, its error, v_c/v_r, D)"""
    out = []
    for least in MIN_COUNTS:
        m = (c["count"] >= least) & (c["P"] > 0)
        v, p, s = c["v"][m], c["P"][m], c["P_err"][m]
        for w in WEIGHTS:
            par, err, _ = fit_p0(v, p, s if w == "Poisson" else p)  # s = P: every weight one
            out.append(dict(weights=w, min_count=least, decades=math.log10(p.max() / p.min()),
                            v_r=par[1], v_r_err=err[1], ratio=par[2] / par[1], d=par[0]))
    return out


def crossover(folder, rows):
    """the crossover fit's v_r and v_c/v_r under each choice, run by run, and the seeds' means"""
    runs = [q for q in rows if os.path.exists(os.path.join(folder, "tables", q["name"],
                                                           "velocity.csv.gz"))]
    if not runs:
        return
    s_vr, s_ratio = CROSSOVER[(0.1, 0.1)]
    print(f"\ncrossover T.5.32 at α = 1 (Table 5.3, ε = 0.1/0.1: v_r = {s_vr}, v_c/v_r = "
          f"{s_ratio}): v_r (m/s) / v_c/v_r by weights and least count a bin holds")
    print("run | " + " | ".join(f"{w} ≥ {k}" for k in MIN_COUNTS for w in WEIGHTS))
    fits = {}
    for q in runs:
        c = table(os.path.join(folder, "tables", q["name"], "velocity.csv"))
        fits[q["name"]] = (c, crossover_choices(c))
        print(q["name"] + " | " + " | ".join(f"{f['v_r']:.4f} / {f['ratio']:.3f}"
                                             for f in fits[q["name"]][1]))
    first = fits[runs[0]["name"]][1]
    print("decades of P taken: " + ", ".join(f"≥ {f['min_count']}: {f['decades']:.1f}"
                                             for f in first if f["weights"] == "Poisson"))
    for w in WEIGHTS:
        for least in (10,):
            vr = np.array([next(f["v_r"] for f in fits[q["name"]][1]
                                if f["weights"] == w and f["min_count"] == least) for q in runs])
            rt = np.array([next(f["ratio"] for f in fits[q["name"]][1]
                                if f["weights"] == w and f["min_count"] == least) for q in runs])
            k = t95(len(vr)) / math.sqrt(len(vr))
            print(f"{w} weights, bins of ≥ {least}: v_r = {vr.mean():.4f} ± "
                  f"{k * vr.std(ddof=1):.4f}, v_c/v_r = {rt.mean():.3f} ± {k * rt.std(ddof=1):.3f} "
                  f"(95 %, {len(vr)} seeds)")
    # how far each curve lies from the points on the log plot: the rms of ln(P/P₀) over the bins of
    # ≥ 10 counts, D refitted for the thesis' row (its D is not printed)
    for q in runs:
        c, fs = fits[q["name"]]
        m = (c["count"] >= 10) & (c["P"] > 0)
        v, lp = c["v"][m], np.log(c["P"][m])

        def rms(vr, vc):
            r = lp - np.log(p0(v, 1.0, vr, vc))
            return float(np.sqrt(np.mean((r - r.mean()) ** 2)))
        best = {w: next(rms(f["v_r"], f["v_r"] * f["ratio"]) for f in fs
                        if f["weights"] == w and f["min_count"] == 10) for w in WEIGHTS}
        print(f"{q['name']}: rms ln(P/P₀) over bins ≥ 10: Table 5.3's row "
              f"{rms(s_vr, s_vr * s_ratio):.3f}, equal-weight fit {best['equal']:.3f}, "
              f"Poisson fit {best['Poisson']:.3f}")
    every = [f["v_r"] for _, fs in fits.values() for f in fs]
    print(f"v_r over every choice and seed: {min(every):.4f} … {max(every):.4f} m/s")
    draw_crossover(folder, runs[0]["name"], *fits[runs[0]["name"]])


def draw_crossover(folder, name, c, fits):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    z = c["count"] > 0
    ax.plot(c["v"][z], c["P"][z], ".", ms=2, color="k", label=f"P(v), {name}")
    vv = np.linspace(c["v"][z].min(), c["v"][z].max(), 600)
    for i, (w, least) in enumerate((("Poisson", 10), ("equal", 10), ("equal", 1000))):
        f = next(f for f in fits if f["weights"] == w and f["min_count"] == least)
        ax.plot(vv, p0(vv, f["d"], f["v_r"], f["v_r"] * f["ratio"]), lw=1, color=f"C{i}",
                label=f"{w} weights, bins ≥ {least}: v_r = {f['v_r']:.3f}, "
                      f"v_c/v_r = {f['ratio']:.2f}")
    s_vr, s_ratio = CROSSOVER[(0.1, 0.1)]
    d = next(f["d"] for f in fits if f["weights"] == "equal" and f["min_count"] == 10)
    ax.plot(vv, p0(vv, d, s_vr, s_vr * s_ratio), "--", lw=1, color="C3",
            label=f"Table 5.3: v_r = {s_vr}, v_c/v_r = {s_ratio}")
    ax.set_yscale("log")
    ax.set_ylim(c["P"][z].min() / 3, c["P"].max() * 3)
    save(fig, ax, os.path.join(folder, "crossover_fits.png"), "v (m/s), one Cartesian component",
         "P(v) (s/m)", "crossover T.5.32 at α = 1, φ = 0.53, L = 0.4 m: the fit's choices")


def save(fig, ax, path, xlabel, ylabel, title):
    import matplotlib.pyplot as plt
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def first_window(rows, box):
    return next(q["window"] for q in rows if q["box"] == box)


def t95(n):
    return {2: 12.706, 3: 4.303, 4: 3.182, 5: 2.776}.get(n, 1.96)


def draw(folder, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    latest = {q["box"]: q for q in rows}  # each box's last row: its latest window
    for i, q in enumerate(latest[b] for b in sorted(latest)):
        c = q["fpc"]
        ok = c["count"] > 0
        ax.plot(c["l"][ok], c["P"][ok], ".", ms=3, color=f"C{i}",
                label=f"L = {q['box']:g} m ({q['window']} s): D_f = {q['fp']['D_f']:.3f}")
        w = ok & (c["l"] >= q["fp"]["l_fit_min"] * (1 - 1e-9))
        ax.plot(c["l"][w], c["P_fit"][w], "-", lw=1, color=f"C{i}")
    ax.axhline(1.0, color="0.6", ls=":", lw=1, label="P_l = 1/m: the fit window's top (§4.3.3)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(1e-6, 1e5)
    save(fig, ax, os.path.join(folder, "freepath_boxes.png"), "l (m)", "P_l (1/m)",
         "free paths, φ = 0.53, ε = 0.1: the tail against the box")


def main(argv):
    if argv and argv[0] == "--collect":
        collect(argv[1], argv[2:])
        return 0
    folder = argv[0] if argv else os.path.join(ROOT, "docs", "reproduction", "investigations",
                                               "rfm")
    report(folder)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

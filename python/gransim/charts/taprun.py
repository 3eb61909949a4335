"""Per-run charts of a tapping study: proof of rest, segregation, stress (docs/physics.md §2.5;
paper section IV and Fig. 12).

Reads ANALYSIS_DIR/runs.csv (written by `gransim analyze`: label, dir, protocol, control, ...)
and each run's taps.csv and segregation.csv, and writes into ANALYSIS_DIR (or --out):

  taprun_rest.png         kinetic energy and largest speed at each measurement, and when each
                          relaxation ended (early rest): the piles are at rest when measured
  taprun_segregation.png  cumulative counts n(h) of big and small grains, prepared pile against
                          the mean over the tapped piles: straight, unchanged lines = no
                          segregation (the paper's test)
  taprun_halves.png       phi of the test rectangle and of its halves against the tap number
  fig12_stress_phi.png    mean force-moment tensor components (P.41) against the mean phi

Needs python3, numpy and matplotlib (Agg). Missing files are skipped with a message.

usage: python3 -m gransim.charts.taprun ANALYSIS_DIR [--out DIR] [--max-runs N]
"""
import argparse
import csv
import json
import math
import os
import sys

import matplotlib

if __name__ == "__main__":  # run as a command: files, not windows; an importer keeps its own
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

NAMES = {"negative_g": ("negative g", "$g_p$ = %g"), "rotating_g": ("rotating g", "$f$ = %g Hz")}


def log(msg):
    print("charts_taprun: " + msg)


def split_line(line, sep):
    return line.split() if sep is None else [c.strip().strip('"') for c in line.split(sep)]


def number(cell, sep):
    # with ';' or tab separators a decimal comma is a point (as the C++ reader takes it)
    if sep not in (",", None) and "," in cell and "." not in cell:
        cell = cell.replace(",", ".")
    return float(cell)


def read_columns(path):
    """a CSV file as {column: numpy array}, separated as gransim analyze reads
    it (',' else ';' or tab else blanks; a single column of numbers is phi); None when missing,
    empty or not numbers"""
    if not os.path.exists(path):
        log("missing %s" % path)
        return None
    with open(path, newline="", encoding="utf-8-sig") as f:
        lines = [s.rstrip("\r\n") for s in f if s.strip() and not s.lstrip().startswith("#")]
    if not lines:
        log("no rows in %s" % path)
        return None
    sep = next((c for c in (",", ";", "\t") if c in lines[0]), None if " " in lines[0].strip() else ",")
    head = split_line(lines[0], sep)
    try:
        if len(head) == 1 and math.isfinite(number(head[0], sep)):
            head, lines = ["phi"], ["phi"] + lines
    except ValueError:
        pass
    try:
        rows = [[number(x, sep) for x in split_line(r, sep)] for r in lines[1:]]
    except ValueError as e:
        log("%s: not numbers (%s)" % (path, e))
        return None
    data = np.array([r for r in rows if len(r) == len(head)])
    if data.size == 0:
        log("no rows in %s" % path)
        return None
    cols = {h: data[:, k] for k, h in enumerate(head)}
    # names in any case (Phi), and taps counted from 1 when the file has no tap column
    for h in head:
        cols.setdefault(h.lower(), cols[h])
    cols.setdefault("tap", np.arange(1.0, len(data) + 1.0))
    return cols


def run_name(r):
    if not r["protocol"] or not math.isfinite(float(r["control"])):
        return r["label"]  # a series of unknown protocol or control
    proto, fmt = NAMES.get(r["protocol"], (r["protocol"], "control = %g"))
    return "%s, %s" % (proto, fmt % float(r["control"]))


def save(fig, out, name, what):
    path = os.path.join(out, name)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    log("wrote %s (%s)" % (path, what))


def pick(runs, n):
    """up to n runs spread over the list"""
    if len(runs) <= n:
        return runs
    idx = sorted(set(np.linspace(0, len(runs) - 1, n).round().astype(int)))
    return [runs[i] for i in idx]


def chart_rest(runs, taps, out):
    fig, (a, b, c) = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for r in runs:
        t = taps[r["label"]]
        k = t["tap"]
        a.semilogy(k, np.maximum(t["kinetic_energy"], 1e-30), ".", ms=3, label=run_name(r))
        b.semilogy(k, np.maximum(t["max_speed"], 1e-30), ".", ms=3)
        early = t["early"] > 0.5
        line = c.plot(k[~early], t["relax_end"][~early], ".", ms=3)[0]
        c.plot(k[early], t["relax_end"][early], "x", ms=4, color=line.get_color())
    a.set_ylabel("kinetic energy (J)")
    a.set_title("state at each measurement, just before the next excitation")
    a.legend(fontsize=7, markerscale=3)
    b.set_ylabel("largest speed (m/s)")
    c.set_ylabel("relaxation ended at (s)")
    c.set_xlabel("tap number")
    c.set_title("time within the period when the relaxation ended (x: early rest)")
    fig.tight_layout()
    save(fig, out, "taprun_rest.png", "proof of rest and early ends")


def chart_segregation(runs, out):
    shown = [r for r in runs if os.path.exists(os.path.join(r["dir"], "segregation.csv"))]
    if not shown:
        log("skip taprun_segregation.png: no segregation.csv")
        return
    fig, axes = plt.subplots(1, len(shown), figsize=(4.2 * len(shown), 4.2), squeeze=False)
    for ax, r in zip(axes[0], shown):
        seg = read_columns(os.path.join(r["dir"], "segregation.csv"))
        if seg is None:
            continue
        species = []
        for name in seg:
            if "@" in name and name.split("@")[0] not in species:
                species.append(name.split("@")[0])
        prepared = seg["tap"] == 0
        tapped = ~prepared
        for k, sp in enumerate(species):
            cols = [n for n in seg if n.startswith(sp + "@")]
            h = np.array([float(n.split("@")[1]) for n in cols]) / 1000.0
            n = np.array([seg[c] for c in cols])  # heights × taps
            if prepared.any():
                ax.plot(n[:, prepared][:, 0], h, "--", color="C%d" % k, lw=1,
                        label="%s, prepared" % sp)
            if tapped.any():
                m = n[:, tapped].mean(axis=1)
                s = n[:, tapped].std(axis=1)
                ax.plot(m, h, "-", color="C%d" % k, label="%s, mean of %d taps" % (sp, tapped.sum()))
                ax.fill_betweenx(h, m - s, m + s, color="C%d" % k, alpha=0.2, lw=0)
        # crop the grid a little above the height where every grain is counted
        allc = np.array([seg[c][-1] for c in seg if "@" in c])
        hh = np.array([float(c.split("@")[1]) for c in seg if "@" in c]) / 1000.0
        full = allc.max() if len(allc) else 0
        top = hh[allc >= 0.999 * full].min() if len(allc) else 1.0
        ax.set_ylim(0, min(hh.max(), top * 1.15 + 0.02))
        ax.set_xlabel("grains below h, n(h)")
        ax.set_ylabel("height h (m)")
        ax.set_title(run_name(r), fontsize=9)
        ax.legend(fontsize=7)
    fig.suptitle("segregation test: cumulative counts per species (band: ±1 s.d. over taps)")
    fig.tight_layout()
    save(fig, out, "taprun_segregation.png", "n(h) per species")


def chart_halves(runs, taps, out):
    fig, axes = plt.subplots(len(runs), 1, figsize=(8, 2.6 * len(runs)), squeeze=False)
    for ax, r in zip(axes[:, 0], runs):
        t = taps[r["label"]]
        keep = t["tap"] > 0
        for col, style in (("phi", "k-"), ("phi_left", "C0-"), ("phi_right", "C3-")):
            ax.plot(t["tap"][keep], t[col][keep], style, lw=0.8, label=col)
        ax.set_ylabel(r"$\phi$")
        ax.set_title(run_name(r), fontsize=9)
        ax.legend(fontsize=7, ncol=3)
    axes[-1, 0].set_xlabel("tap number")
    fig.tight_layout()
    save(fig, out, "taprun_halves.png", "phi of the test rectangle and its halves")


def chart_stress(runs, taps, discard, out):
    pts = []
    for r in runs:
        t = taps[r["label"]]
        keep = t["tap"] > discard
        if keep.sum() < 2:
            continue
        pts.append((r, t["phi"][keep].mean(), {c: t[c][keep] for c in ("S_xx", "S_yy", "S_xy", "S_yx")}))
    if not pts:
        log("skip fig12_stress_phi.png: no runs with taps after the transient")
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    marks = {"negative_g": "D", "rotating_g": "x"}
    for comp, color in (("S_xx", "C0"), ("S_yy", "C3"), ("S_xy", "C2")):
        for proto in sorted({p[0]["protocol"] for p in pts}):
            sel = [p for p in pts if p[0]["protocol"] == proto]
            x = [p[1] for p in sel]
            y = [p[2][comp].mean() for p in sel]
            e = [p[2][comp].std(ddof=1) / math.sqrt(len(p[2][comp])) for p in sel]
            ax.errorbar(x, y, yerr=e, fmt=marks.get(proto, "o"), color=color, capsize=2,
                        label="%s, %s" % (comp, NAMES.get(proto, (proto,))[0]))
    ax.set_xlabel(r"mean volume fraction $\bar\phi$")
    ax.set_ylabel(r"force-moment tensor $S_{ab}$ (N m), mean over taps")
    ax.set_title("extensive stress against packing (paper Fig. 12; error: s.e.m.)")
    ax.legend(fontsize=7)
    save(fig, out, "fig12_stress_phi.png", "stress tensor vs phi")


def main(argv=None):
    """the command line (argv: its arguments; default sys.argv[1:])"""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("analysis_dir")
    ap.add_argument("--out", help="folder for the PNGs (default: the analysis folder)")
    ap.add_argument("--max-runs", type=int, default=4, help="runs in the per-run charts (default 4)")
    a = ap.parse_args(argv)
    out = a.out or a.analysis_dir
    os.makedirs(out, exist_ok=True)
    path = os.path.join(a.analysis_dir, "runs.csv")
    if not os.path.exists(path):
        log("no runs.csv in %s: nothing to chart" % a.analysis_dir)
        return 1
    with open(path, newline="") as f:
        runs = list(csv.DictReader(f))
    discard = 10
    info = os.path.join(a.analysis_dir, "analysis.json")
    if os.path.exists(info):
        with open(info) as f:
            discard = json.load(f).get("discard", discard)
    taps = {}
    for r in runs:
        t = read_columns(r.get("file") or os.path.join(r["dir"], "taps.csv"))
        if t is not None:
            taps[r["label"]] = t
    runs = [r for r in runs if r["label"] in taps]
    if not runs:
        log("no taps.csv of any run: nothing to chart")
        return 1
    few = pick(runs, a.max_runs)

    # each chart needs its own columns: a series from elsewhere (tap, phi only) skips the rest
    def having(rs, cols, chart):
        ok = [r for r in rs if all(c in taps[r["label"]] for c in cols)]
        if len(ok) < len(rs):
            log("%s: %d of %d runs lack %s" % (chart, len(rs) - len(ok), len(rs), ", ".join(cols)))
        return ok

    # plain series (an experiment's) have none of a run's own columns: only their halves, if any
    if all(r.get("status") == "plain" for r in runs):
        halves = [r for r in few if all(c in taps[r["label"]] for c in ("phi_left", "phi_right"))]
        if halves:
            chart_halves(halves, taps, out)
        return 0
    rest = having(runs, ("tap", "kinetic_energy", "max_speed", "early", "relax_end"), "taprun_rest.png")
    if rest:
        chart_rest(rest, taps, out)
    chart_segregation(few, out)
    halves = having(few, ("tap", "phi", "phi_left", "phi_right"), "taprun_halves.png")
    if halves:
        chart_halves(halves, taps, out)
    stress = having(runs, ("tap", "phi", "S_xx", "S_yy", "S_xy", "S_yx"), "fig12_stress_phi.png")
    if stress:
        chart_stress(stress, taps, discard, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())

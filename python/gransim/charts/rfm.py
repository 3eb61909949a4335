"""Charts of the Random Force Model analyses (thesis chapters 2-6).

Reads the CSV files written by the gs::rfm and gs::models write_*_csv helpers (one header line,
numeric rows; metadata in NAME.json beside, or "# key=value" lines above the header in older files) from a directory and draws one PNG per file:

  temperature.csv  T(t) with block means                          -> temperature.png
  velocity.csv     P(v) log-linear, tail and crossover fits       -> velocity.png
  tail_scan.csv    chi2_r against alpha, accepted range           -> tail_scan.png
  lnln_A0.csv,     ln(-ln(P/A)) against ln(v/v_rms) for A = A0    -> lnln.png
  lnln_P0.csv        and for A = P(0) (thesis section 5.3.3)
  sk.csv           S(k) log-log, D_f fit line, k_D marked         -> sk.png
  gr.csv           g(R)                                           -> gr.png
  gh.csv           G_h(R), h = 1, 2, 4, 8                         -> gh.png
  freepath.csv     P_l(l) log-log with the fit of T.4.25          -> freepath.png
  bisection.csv    segment lengths against (-ln x)^(n-1)/(n-1)!   -> bisection.png
  walk_l*.csv      Q(v, l) collapsed in v/l^(1/3)                 -> walks.png
  heating.csv      <v_x^2>(t) and <x^2>(t) of free particles      -> heating.png
  interval.csv     arrival velocities at x = L against B.32       -> interval.png
  cascade_*.csv    cascade S(k), exact expectation, fit, D2       -> cascade_*.png
and, drawn by gransim.charts.rfm_compare:
  gh_bisection.csv, gh.csv  1D G_h(R) against the bisection (T.3.25, T.3.36) -> gh_bisection.png
  velocity.csv + velocity_post.csv (or hist_velocity.csv + hist_postcollision.csv)
                   post-collision against overall P(v), log-linear -> postcollision.png
  moments_vs_N.csv, exponents.csv  <|v|^m>, <R^m> against N, xi_m, zeta_m -> moments_vs_N.png

Usage: python3 -m gransim.charts.rfm CSV_DIR [--out PNG_DIR] [--bisection BISECTION_CSV] [--no-parent]
`gransim analyze` calls this once per run folder OUT/<run>; the across-run chart
moments_vs_N.png of OUT itself is drawn when CSV_DIR is OUT, and also (unless --no-parent)
from the last run folder listed in OUT/rfm_summary.json. --bisection adds the G_1, G_2 of a
`gransim model bisection` output to gh_bisection.png (default: CSV_DIR/bisection.csv if present).
Missing files are skipped with a note. Needs numpy and matplotlib (Debian: python3-matplotlib;
on machines where `python3` is another interpreter, run it with /usr/bin/python3).
"""
import argparse
import glob
import json
import math
import os
import sys

try:
    import matplotlib
    if __name__ == "__main__":  # run as a command: files, not windows
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
except ImportError as e:  # pragma: no cover
    sys.exit(f"gransim.charts.rfm needs numpy and matplotlib ({e}); try /usr/bin/python3")


def read_csv(path):
    """metadata dict and a dict of numpy columns (metadata from the sidecar NAME.json, or from
    the "# key=value" lines that older files have above the header)"""
    meta, names, rows = {}, None, []
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            if line.startswith("#"):
                if "=" in line:
                    k, v = line.lstrip("# ").split("=", 1)
                    meta[k.strip()] = float(v)
                continue
            if names is None:
                names = [c.strip() for c in line.split(",")]
                continue
            rows.append([float(c) for c in line.split(",")])
    data = np.array(rows) if rows else np.zeros((0, len(names)))
    meta.update(read_meta(path))
    return meta, {n: data[:, i] for i, n in enumerate(names)}


def read_meta(path):
    """the metadata sidecar NAME.json of NAME.csv ({} when absent; null reads as nan)"""
    side = os.path.splitext(path)[0] + ".json"
    if not os.path.exists(side):
        return {}
    with open(side) as f:
        return {k: math.nan if v is None else float(v) for k, v in json.load(f).items()}


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    print("wrote", path)


def temperature(src, out):
    m, c = read_csv(src)
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(c["t"], c["T"], lw=0.6, color="0.55", label="T(t) (T.2.19)")
    if "T_block" in c:
        ax.plot(c["t"], c["T_block"], lw=1.8, color="C3", label="block means (T.2.20)")
    if "T_mean" in m:
        ax.axhline(m["T_mean"], color="C0", ls="--",
                   label=f"<T> = {m['T_mean']:.4g} ± {m['T_err']:.2g}")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("T (m²/s²)")
    ax.set_title("granular temperature")
    ax.legend()
    save(fig, out, "temperature.png")


def velocity(src, out):
    m, c = read_csv(src)
    ok = c["count"] > 0
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.errorbar(c["v"][ok], c["P"][ok], yerr=c["P_err"][ok], fmt=".", ms=3, color="k",
                elinewidth=0.6, label="P(v), Poisson errors (T.A.5)")
    if "alpha_best" in m:
        lo, hi = m.get("alpha_lo", float("nan")), m.get("alpha_hi", float("nan"))
        acc = (f"accepted [{lo:.2f}, {hi:.2f}]" if not math.isnan(lo)
               else f"none accepted (χ²_r = {m.get('tail_chi2_r', float('nan')):.2g} > 1.2)")
        for side in (c["v"] < 0, c["v"] > 0):  # the fit window on each side
            ax.plot(c["v"][side], c["P_tail"][side], "-", color="C1", lw=2.5, alpha=0.8,
                    label=f"A exp(−B|v|^α) on the fit window: best α = {m['alpha_best']:.2f}, "
                          f"{acc}" if side[-1] else None)
    if "cross_D" in m:
        ax.plot(c["v"], c["P_cross"], "-", color="C0", lw=1.2,
                label=f"crossover T.5.32: v_r = {m['cross_v_r']:.3g}, v_c = {m['cross_v_c']:.3g}, α = {m['cross_alpha']:.2g}")
    ax.set_yscale("log")
    pos = c["P"][ok]
    ax.set_ylim(0.3 * pos.min(), 8 * pos.max())
    vmax = np.abs(c["v"][ok]).max()
    ax.set_xlim(-1.05 * vmax, 1.05 * vmax)
    ax.set_xlabel("v (m/s)")
    ax.set_ylabel("P(v) (s/m)")
    ax.set_title("velocity distribution (one component)")
    ax.legend(fontsize=7, loc="upper left", framealpha=0.9)
    save(fig, out, "velocity.png")


def tail_scan(src, out):
    m, c = read_csv(src)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(c["alpha"], c["chi2_r"], color="k")
    ax.axhline(1.2, color="C3", ls="--", label="χ²_r = 1.2 (appendix A)")
    if not math.isnan(m.get("alpha_lo", float("nan"))):
        ax.axvspan(m["alpha_lo"], m["alpha_hi"], color="C2", alpha=0.2,
                   label=f"accepted α ∈ [{m['alpha_lo']:.2f}, {m['alpha_hi']:.2f}]")
    ax.axvline(m["alpha_best"], color="C0", lw=0.8, label=f"best α = {m['alpha_best']:.2f}")
    ax.set_yscale("log")
    ax.set_ylim(min(0.5, 0.8 * np.nanmin(c["chi2_r"])), None)
    ax.set_xlabel("α (dimensionless)")
    ax.set_ylabel("χ²_r of ln P against |v|^α")
    acc = "none accepted" if math.isnan(m.get("alpha_lo", float("nan"))) else "accepted range shaded"
    ax.set_title(f"stretched-exponential tail scan ({acc})")
    ax.legend(fontsize=8)
    save(fig, out, "tail_scan.png")


def lnln(srcs, out):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for src, col in zip(srcs, ["C0", "C3"]):
        m, c = read_csv(src)
        label = "A = A₀ (asymptotic)" if "A0" in os.path.basename(src) else "A = P(0)"
        ax.errorbar(c["ln_v"], c["y"], yerr=c["y_err"], fmt=".", ms=3, color=col, elinewidth=0.5,
                    label=f"{label} = {m['A']:.3g} s/m")
        tail = c["ln_v"] > 0.8
        if tail.sum() >= 3:
            p = np.polyfit(c["ln_v"][tail], c["y"][tail], 1)
            xs = np.linspace(0.0, c["ln_v"].max() + 0.4, 10)
            ax.plot(xs, np.polyval(p, xs), "--", color=col, lw=1.2,
                    label=f"line fitted on ln(v/v_rms) > 0.8: slope {p[0]:.2f}")
    ys = []
    for src in srcs:  # the y range of the points with usable errors (a lone bin can reach −20)
        _, c = read_csv(src)
        good = np.isfinite(c["y"]) & (c["y_err"] < 0.5)
        ys.extend(c["y"][good])
    if ys:
        ax.set_ylim(min(ys) - 0.5, max(ys) + 0.8)
    ax.set_xlabel("ln(|v| / v_rms) (dimensionless)")
    ax.set_ylabel("ln(−ln(P/A)) (dimensionless)")
    ax.set_title("ln–ln tail plot: slope = α of a stretched exponential")
    ax.legend(fontsize=8)
    save(fig, out, "lnln.png")


def structure_factor(src, out):
    m, c = read_csv(src)
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.errorbar(c["k"], c["S"], yerr=c["S_err"], fmt=".", ms=3, color="k", elinewidth=0.5,
                label="S(k), shells of equal |k|")
    if "D_f" in m:
        sel = (c["k"] >= m["k_lo"]) & (c["k"] <= m["k_hi"])
        ks = np.linspace(c["k"][sel].min(), c["k"][sel].max(), 20)
        ax.plot(ks, m["A"] * ks ** (-m["D_f"]), color="C3", lw=2,
                label=f"A k^(−D_f), D_f = {m['D_f']:.3f} ± {m['D_f_err']:.3f}"
                      + (f", χ²_r = {m['chi2_r']:.2g}" if "chi2_r" in m else "")
                      + f", {int(sel.sum())} shells")
        ax.axvspan(c["k"][sel].min() / 1.15, m["k_hi"], color="C3", alpha=0.08,
                   label=f"fit window k ≤ k′ = {m['k_hi']:.3g} 1/m (T.4.9)")
    if m.get("k_D", 0) > 0:
        ax.axvline(m["k_D"], color="C0", ls=":", label=f"k_D = {m['k_D']:.3g} 1/m (L_Eff = {m['L_eff']:.3g} m)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("k (1/m)")
    ax.set_ylabel("S(k) (dimensionless)")
    ax.set_title("structure factor S(k) (T.4.2), power-law fit below k′")
    ax.legend(fontsize=8)
    save(fig, out, "sk.png")


def pair_correlation(src, out):
    _, c = read_csv(src)
    fig, ax = plt.subplots(figsize=(6.5, 4))
    ax.errorbar(c["R"], c["g"], yerr=c["g_err"], fmt=".-", ms=3, lw=0.6, color="k", elinewidth=0.5,
                label="g(R), minimum image")
    ax.axhline(1.0, color="C3", ls="--", label="ideal gas")
    ax.set_xlabel("R (m)")
    ax.set_ylabel("g(R) (dimensionless)")
    ax.set_title("pair correlation (T.4.10)")
    ax.legend()
    save(fig, out, "gr.png")


def gap_distributions(src, out):
    _, c = read_csv(src)
    hs = [n[1:] for n in c if n.startswith("G") and not n.endswith("_err")]
    fig, axs = plt.subplots(1, 2, figsize=(11, 4.3))
    for h in hs:
        ok = c["G" + h] > 0
        axs[0].plot(c["R"][ok], c["G" + h][ok], ".-", ms=3, lw=0.7, label=f"h = {h}")
        axs[1].plot(-np.log(c["R"][ok]), c["G" + h][ok], ".-", ms=3, lw=0.7, label=f"h = {h}")
    axs[0].set_xscale("log")
    axs[0].set_xlabel("R (units of L′)")
    axs[1].set_xlabel("−ln R (R in units of L′)")
    axs[1].set_xscale("log")
    for ax in axs:
        ax.set_yscale("log")
        ax.set_ylabel("G_h(R) (1/L′)")
        ax.legend(fontsize=8)
    axs[0].set_title("h-th neighbour distributions (T.3.24)")
    axs[1].set_title("the same against −ln R (thesis Fig. 3.12)")
    save(fig, out, "gh.png")


def free_paths(src, out):
    m, c = read_csv(src)
    ok = c["count"] > 0
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.errorbar(c["l"][ok], c["P"][ok], yerr=c["P_err"][ok], fmt=".", ms=3, color="k",
                elinewidth=0.5, label="P_l(l), log bins")
    if "D_f" in m:
        # `gransim analyze` fits the tail (P_l < 1/m, from l_fit_min on; older tables: l >= d/10)
        l_min, where = float(m.get("l_fit_min", 0.0)), "the tail, P_l < 1/m"
        if not l_min:
            where = "l = d/10"
            try:
                with open(os.path.join(os.path.dirname(src), "rfm.json")) as f:
                    l_min = 0.1 * float(json.load(f)["diameter"])
            except (OSError, ValueError, KeyError, TypeError):
                pass
        fit = ok & (c["l"] >= l_min)
        chi = f", χ²_r = {m['chi2_r']:.2g}" if "chi2_r" in m else ""
        ax.plot(c["l"][fit], c["P_fit"][fit], color="C3", lw=1.8,
                label=f"T.4.25 fit: D_f = {m['D_f']:.3f} ± {m['D_f_err']:.3f}, C = {m['C']:.3g}{chi}")
        if l_min > 0 and (ok & ~fit).any():
            below = ok & (c["l"] <= c["l"][fit].min())
            ax.plot(c["l"][below], c["P_fit"][below], "--", color="C3", lw=1,
                    label="the same extrapolated below the fit range")
            ax.axvline(l_min, color="0.5", ls=":", lw=1, label=f"fit from {where}: l = {l_min:.2g} m")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("l (m)")
    ax.set_ylabel("P_l (1/m)")
    ax.set_title("free-path distribution P_l(l) with the fit of T.4.25")
    ax.legend(fontsize=8)
    save(fig, out, "freepath.png")


def bisection(src, out):
    m, c = read_csv(src)
    n = int(m["levels"])
    ok = c["P"] > 0
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.errorbar(c["x"][ok], c["P"][ok], yerr=c["P_err"][ok], fmt="o", ms=3, mfc="none", color="k",
                elinewidth=0.5, label=f"segments, n = {n}")
    ax.plot(c["x"], c["P_exact"], color="C3", label="(−ln x)^(n−1)/(n−1)! (T.3.36)")
    ax.plot(c["x"][ok], c["G1"][ok], "x", ms=4, color="C0", label="G₁ of the boundaries (T.3.21)")
    ok2 = c["G2"] > 0
    ax.plot(c["x"][ok2], c["G2"][ok2], "+", ms=4, color="C2", label="G₂ of the boundaries")
    ax.plot(c["x"], c["P_exact_prev"], "--", color="C2", lw=0.8, label=f"P_(n−1) (T.3.25 partner of G₂)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(1e-6, None)
    ax.set_xlabel("x (fraction of the interval)")
    ax.set_ylabel("density")
    ax.set_title("uniform multiplicative bisection")
    ax.legend(fontsize=8)
    save(fig, out, "bisection.png")


def walks(srcs, out):
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for src in srcs:
        m, c = read_csv(src)
        ok = c["count"] > 0
        ax.plot(c["u"][ok], c["Q_scaled"][ok], ".", ms=3,
                label=f"l = {m['radius']:.3g}: <τ> = {m['mean_exit_time']:.3g} s")
    ax.set_yscale("log")
    ax.set_xlabel("u = v / (D l/M²)^(1/3)")
    ax.set_ylabel("Q(v, l)·(D l/M²)^(1/3)")
    ax.set_title("single-particle walk in a disc: Q collapses in v/l^(1/3)")
    ax.legend(fontsize=8)
    save(fig, out, "walks.png")


def heating(src, out):
    _, c = read_csv(src)
    fig, axs = plt.subplots(1, 2, figsize=(11, 4))
    axs[0].errorbar(c["t"], c["v2"], yerr=c["v2_err"], fmt=".", ms=3, color="k", elinewidth=0.5,
                    label="free particles")
    axs[0].plot(c["t"], c["v2_exact"], color="C3", label="2 D t/M²")
    axs[0].set_ylabel("<v_x²> (m²/s²)")
    axs[1].errorbar(c["t"], c["x2"], yerr=c["x2_err"], fmt=".", ms=3, color="k", elinewidth=0.5,
                    label="free particles")
    axs[1].plot(c["t"], c["x2_exact"], color="C3", label="(2/3) D t³/M² (discrete form)")
    axs[1].set_xscale("log")
    axs[1].set_yscale("log")
    axs[1].set_ylabel("<x²> (m²)")
    for ax in axs:
        ax.set_xlabel("t (s)")
        ax.legend(fontsize=8)
    axs[0].set_title("noise heating")
    axs[1].set_title("ballistic-diffusive spreading")
    save(fig, out, "heating.png")


def interval(src, out):
    m, c = read_csv(src)
    ok = c["count"] > 0
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.errorbar(c["u"][ok], c["f"][ok], yerr=c["f_err"][ok], fmt="o", ms=3, mfc="none", color="k",
                elinewidth=0.5, label=f"walks: <τ> = {m['mean_exit_time']:.4f} ± {m['exit_time_err']:.4f}")
    ax.plot(c["u"], c["f_theory"], color="C3",
            label=f"appendix B (B.32): <τ> = {m['mean_exit_time_theory']:.4f}")
    ax.set_xlabel("u = v / (D L/M²)^(1/3)")
    ax.set_ylabel("density of arrival velocities at x = L")
    ax.set_title("1D interval, release at rest at uniform x (thesis Fig. B.1)")
    ax.legend(fontsize=8)
    save(fig, out, "interval.png")


def cascade(src, out):
    m, c = read_csv(src)
    name = os.path.splitext(os.path.basename(src))[0]
    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    ax.errorbar(c["k"], c["S"], yerr=c["S_err"], fmt=".", ms=3, color="k", elinewidth=0.5,
                label="measured (FFT, configuration average)")
    ax.plot(c["k"], c["S_exact"], color="C0", lw=0.8, label="exact E[S(k)]")
    if "D_f" in m:
        ks = np.linspace(m["k_lo"], m["k_hi"], 20)
        ax.plot(ks, m["A"] * ks ** (-m["D_f"]), color="C3", lw=2,
                label=f"fit D_f = {m['D_f']:.3f} ± {m['D_f_err']:.3f} (D₂ = {m['D2']:.4f})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("k (1/m)")
    ax.set_ylabel("S(k) (T.6.5)")
    ax.set_title(f"multiplicative cascade: {name.split('_', 1)[-1]}")
    ax.legend(fontsize=8)
    save(fig, out, name + ".png")


def last_run_of_parent(csv_dir):
    """the analysis folder above CSV_DIR when CSV_DIR is the last run its rfm_summary.json
    lists (so the across-run charts are drawn once, after every run's files exist)"""
    here = os.path.abspath(csv_dir)
    parent = os.path.dirname(here)
    summary = os.path.join(parent, "rfm_summary.json")
    if not (os.path.exists(summary) and os.path.exists(os.path.join(parent, "moments_vs_N.csv"))):
        return None
    try:
        with open(summary) as f:
            runs = json.load(f)["runs"]
        return parent if runs and runs[-1]["label"] == os.path.basename(here) else None
    except (OSError, ValueError, KeyError, TypeError):
        return parent


def compare_charts(csv_dir, out, bisection_csv, parent_too):
    """the charts of gransim.charts.rfm_compare; a failure of one is reported, never fatal"""
    # run as a script (python3 -m), this module is __main__: rfm_compare imports it, not a copy
    sys.modules.setdefault(__package__ + ".rfm", sys.modules[__name__])
    from . import rfm_compare as cmp
    jobs = []
    if os.path.exists(os.path.join(csv_dir, "gh_bisection.csv")) or os.path.exists(os.path.join(csv_dir, "gh.csv")):
        jobs.append(("gh_bisection", lambda: cmp.gh_bisection(csv_dir, out, bisection_csv)))
    else:
        print("skipped (missing):", os.path.join(csv_dir, "gh_bisection.csv"))
    jobs.append(("postcollision", lambda: cmp.postcollision(csv_dir, out)))
    if os.path.exists(os.path.join(csv_dir, "moments_vs_N.csv")):
        jobs.append(("moments_vs_N", lambda: cmp.moments_vs_n(csv_dir, out)))
    parent = last_run_of_parent(csv_dir) if parent_too else None
    if parent:
        jobs.append(("moments_vs_N of " + parent, lambda: cmp.moments_vs_n(parent, parent)))
    for name, job in jobs:
        try:
            job()
        except Exception as e:  # a chart of odd data is skipped, the others still drawn
            plt.close("all")
            print(f"skipped ({type(e).__name__}: {e}): {name}")


def main(argv=None):
    """the command line (argv: its arguments; default sys.argv[1:])"""
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv_dir")
    ap.add_argument("--out", default=None, help="where the PNGs go (default: CSV_DIR)")
    ap.add_argument("--bisection", default=None,
                    help="bisection.csv of `gransim model bisection` to overlay on gh_bisection.png")
    ap.add_argument("--no-parent", action="store_true",
                    help="do not draw the across-run charts of the folder above CSV_DIR")
    a = ap.parse_args(argv)
    out = a.out or a.csv_dir
    os.makedirs(out, exist_ok=True)
    p = lambda n: os.path.join(a.csv_dir, n)
    jobs = [("temperature.csv", temperature), ("velocity.csv", velocity), ("tail_scan.csv", tail_scan),
            ("sk.csv", structure_factor), ("gr.csv", pair_correlation), ("gh.csv", gap_distributions),
            ("freepath.csv", free_paths), ("bisection.csv", bisection), ("heating.csv", heating),
            ("interval.csv", interval)]
    for name, fn in jobs:
        if os.path.exists(p(name)):
            fn(p(name), out)
        else:
            print("skipped (missing):", p(name))
    ll = [f for f in (p("lnln_A0.csv"), p("lnln_P0.csv")) if os.path.exists(f)]
    if ll:
        lnln(ll, out)
    wk = sorted(glob.glob(p("walk_l*.csv")))
    if wk:
        walks(wk, out)
    for f in sorted(glob.glob(p("cascade_*.csv"))):
        cascade(f, out)
    bis = a.bisection or (p("bisection.csv") if os.path.exists(p("bisection.csv")) else None)
    compare_charts(a.csv_dir, out, bis, not a.no_parent and a.out is None)


if __name__ == "__main__":
    main()

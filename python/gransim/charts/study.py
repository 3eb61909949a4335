"""Charts of `gransim study DIR`: error against cost per reference problem (log-log, one curve
per integrator and switch set, Pareto front marked, statistical-error band where one exists),
and the stability map (largest stable dt in contact times per integrator and model).

usage: python3 -m gransim.charts.study DIR   (reads DIR/study.csv, DIR/stability.csv; writes DIR/*.png)
"""
import csv
import math
import os
import sys

import matplotlib

if __name__ == "__main__":  # run as a command: files, not windows; an importer keeps its own
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLORS = {"gear6": "tab:blue", "velocity_verlet": "tab:orange",
          "position_verlet": "tab:green", "semi_implicit_euler": "tab:red"}
STYLES = ["-", "--", ":", "-."]
MARKERS = ["o", "s", "^", "v", "D"]
YLABEL = {
    "restitution_rel_error_vs_exact": "|ε_realised − ε| / ε",
    "restitution_rel_error_vs_reference": "|ε − ε_ref| / ε_ref (ref: Gear 6, smallest Δt)",
    "energy_drift_per_s": "|ΔE| / E per simulated second (1/s)",
    "haff_slope_rel_error_vs_enskog": "|slope / Enskog − 1|",
    "phi_abs_error_vs_reference": "|φ − φ_ref| (ref: Gear 6, smallest Δt)",
    "phi_mean_abs_error_vs_reference": "|φ̄ − φ̄_ref| (ref: Gear 6, small Δt, full relaxations)",
    "temperature_rel_error_vs_reference": "|⟨T⟩ − ⟨T⟩_ref| / ⟨T⟩_ref (ref: Gear 6, small Δt)",
    "sd_phi_mean_abs_error_vs_reference": "|σ_φ − σ_φ,ref| (ref: Gear 6, small Δt, full relaxations)",
    "sd_temperature_rel_error_vs_reference": "|σ_T − σ_T,ref| / σ_T,ref",
}


def num(s):
    try:
        v = float(s)
    except ValueError:
        return math.nan
    return v


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def pareto(points):
    """non-dominated (cost, error) points, sorted by cost: cheaper or more accurate than all"""
    front, best = [], math.inf
    for c, e in sorted(points):
        if e < best:
            front.append((c, e))
            best = e
    return front


def cost_of(rows):
    """the cost column: wall time per tap where the problem reports one (tapping: early rest
    shortens the simulated time, so per simulated second would hide its gain), else per
    simulated second"""
    if rows and all(num(r.get("wall_per_tap_s", "nan")) > 0 for r in rows
                    if r["stable"] == "true"):
        return "wall_per_tap_s", "cost: wall time per tap (s)"
    return "wall_per_sim_s", "cost: wall time per simulated second (s/s)"


def band_of(rows, col):
    """the statistical error of the study: the median over the stable rows (0: none)"""
    v = sorted(num(r.get(col, "nan")) for r in rows if r["stable"] == "true")
    v = [x for x in v if x > 0]
    return v[len(v) // 2] if v else 0.0


def error_chart(problem, rows, out, err_col="error", stat_col="stat_error", kind=None):
    many = len({(r["integrator"], r["switches"], r["broad_phase"]) for r in rows}) > 6
    cost_col, cost_label = cost_of(rows)
    fig, ax = plt.subplots(figsize=(12.5, 6.0) if many else (7.5, 5.2))
    unstable = {}
    switches = sorted({r["switches"] for r in rows})
    # switch words shared by every curve say nothing: leave them out of the labels
    common = set.intersection(*[set(sw.split()) for sw in switches]) if switches else set()
    bps = sorted({r["broad_phase"] for r in rows})
    pts = []
    stat = band_of(rows, stat_col)
    curves = {}
    for r in rows:
        key = (r["integrator"], r["switches"], r["broad_phase"])
        curves.setdefault(key, []).append(r)
    for (integ, sw, bp), rs in sorted(curves.items()):
        ok = [(num(r[cost_col]), num(r[err_col]), num(r["dt_over_tc"])) for r in rs
              if r["stable"] == "true" and num(r[err_col]) > 0 and num(r[cost_col]) > 0]
        bad = [r for r in rs if r["stable"] != "true"]
        label = integ
        if len(switches) > 1:
            label += " " + " ".join(w for w in sw.split() if w not in common)
        if len(bps) > 1:
            label += " " + bp
        ls = STYLES[(switches.index(sw) + 2 * bps.index(bp)) % len(STYLES)]
        mk = MARKERS[switches.index(sw) % len(MARKERS)]
        color = COLORS.get(integ, "black")
        if ok:
            ok.sort()
            ax.plot([p[0] for p in ok], [p[1] for p in ok], ls, marker=mk, color=color,
                    label=label, alpha=0.85)
            for c, e, d in ok:
                ax.annotate(f"{d:g}", (c, e), fontsize=6, xytext=(3, 3),
                            textcoords="offset points", color=color)
            pts += [(c, e) for c, e, _ in ok]
        if bad:
            unstable[integ] = unstable.get(integ, 0) + len(bad)
    for integ, n_bad in sorted(unstable.items()):
        ax.plot([], [], "x", color=COLORS.get(integ, "black"), label=f"{integ}: {n_bad} unstable")
    if pts:
        front = pareto(pts)
        ax.plot([p[0] for p in front], [p[1] for p in front], "k-", lw=2.5, alpha=0.25,
                label="Pareto front", zorder=0)
        ax.plot([p[0] for p in front], [p[1] for p in front], "o", mfc="none", mec="black",
                ms=11, zorder=0)
        ax.set_xscale("log")
        ax.set_yscale("log")
        if stat > 0:
            lo = min(min(p[1] for p in pts), stat) / 3
            ax.axhspan(lo, stat, color="grey", alpha=0.18,
                       label=f"statistical error ({stat:.2g}): below = accurate enough")
    else:
        ax.text(0.5, 0.5, "no stable point with an error", ha="center", transform=ax.transAxes)
    if kind is None:
        kind = rows[0]["error_kind"] if rows else ""
    ax.set_xlabel(cost_label)
    ax.set_ylabel(YLABEL.get(kind, kind))
    n = rows[0]["particles"] if rows else "?"
    title = f"{problem} ({n} particles): error against cost; labels = Δt / t_c"
    if common and len(switches) > 1:
        title += "\n(all: " + " ".join(sorted(common)) + ")"
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    if many:
        ax.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    else:
        ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def stability_chart(rows, out):
    groups = sorted({(r["problem"], r["switches"]) for r in rows})
    integs = []
    for r in rows:
        if r["integrator"] not in integs:
            integs.append(r["integrator"])
    fig, ax = plt.subplots(figsize=(max(7.0, 1.3 * len(groups) + 3), 5.0))
    width = 0.8 / max(1, len(integs))
    for k, integ in enumerate(integs):
        xs, hs, capped = [], [], []
        for g, (p, sw) in enumerate(groups):
            for r in rows:
                if r["problem"] == p and r["switches"] == sw and r["integrator"] == integ:
                    xs.append(g + (k - (len(integs) - 1) / 2) * width)
                    hs.append(num(r["max_stable_dt_over_tc"]))
                    capped.append(num(r["first_unstable_dt_over_tc"]) == 0)
        bars = ax.bar(xs, hs, width, label=integ, color=COLORS.get(integ, "grey"))
        for b, h, c in zip(bars, hs, capped):
            ax.annotate(f"{h:.2g}" + ("+" if c else ""), (b.get_x() + b.get_width() / 2, h),
                        ha="center", va="bottom", fontsize=7)
    ax.set_xticks(range(len(groups)))
    ax.set_xticklabels([p + "\n" + sw.replace(" ", "\n").replace("finite_difference", "fd")
                        for p, sw in groups], fontsize=7)
    ax.set_ylabel("largest stable Δt / contact time")
    ax.set_title("stability map (Δt sweep until blow-up; '+' = stable up to the sweep's end)")
    ax.grid(True, axis="y", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main(argv=None):
    """the command line (argv: its arguments; default sys.argv[1:])"""
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1:
        print(__doc__, file=sys.stderr)
        return 2
    d = argv[0]
    rows = read_rows(os.path.join(d, "study.csv"))
    problems = []
    for r in rows:
        if r["problem"] not in problems:
            problems.append(r["problem"])
    for p in problems:
        prow = [r for r in rows if r["problem"] == p]
        error_chart(p, prow, os.path.join(d, f"error_cost_{p}.png"))
        # the statistical problems: the spread (σ_φ, σ_T) against its reference as well
        if any(num(r.get("sd_error", "nan")) >= 0 for r in prow):
            error_chart(p + " spread", prow, os.path.join(d, f"error_cost_{p}_sd.png"),
                        "sd_error", "sd_stat_error", "sd_" + prow[0]["error_kind"])
    stab = os.path.join(d, "stability.csv")
    if os.path.exists(stab):
        srows = read_rows(stab)
        if srows:
            stability_chart(srows, os.path.join(d, "stability_map.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Charts of the tapping study (docs/physics.md §2.6; the tapping paper's Figs 4-11 and 13).

Reads the folder written by the C++ tapping analysis (gs::analyze_tapping: summary.csv,
series.csv, kde.csv, q_lines.csv, beta.csv, quadron.json, analysis.json) and writes PNG charts
into the same folder (or --out). Needs only python3, numpy and matplotlib (Agg backend).
A chart whose protocol or data is missing is skipped with a message; the script does not fail.

usage: python3 -m gransim.charts.tapping ANALYSIS_DIR [--out DIR] [--max-series N]
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

# the protocols of the paper, their control parameter and its unit
PROTOCOLS = {
    "negative_g": ("negative g", "pulse strength $g_p$ (units of g)"),
    "rotating_g": ("rotating g", "rotation frequency $f$ (Hz)"),
}
# figure numbers of the paper per protocol: (φ̄ and σ_φ, KDE/Q/β panel)
FIGNUM = {"negative_g": ("5", "7"), "rotating_g": ("6", "8")}
PHI = r"volume fraction $\phi$"
BETA = r"$\beta$ (m$^{-2}$)"


def log(msg):
    print("charts_tapping: " + msg)


# ---- reading -------------------------------------------------------------------------------

def read_csv(path, quiet=False):
    """rows of a CSV file as dicts of strings; None when the file is missing"""
    if not os.path.exists(path):
        if not quiet:
            log("missing %s" % path)
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(s):
    try:
        return float(s)
    except (TypeError, ValueError):
        return math.nan


def read_json(path, quiet=False):
    if not os.path.exists(path):
        if not quiet:
            log("missing %s" % path)
        return None
    with open(path) as f:
        return json.load(f)


def protocol_name(p):
    return PROTOCOLS.get(p, (p or "series", "control parameter"))[0]


def control_label(p):
    return PROTOCOLS.get(p, (p, "control parameter"))[1]


def protocols_in(rows):
    """the protocols present, known ones first in the paper's order"""
    seen = []
    for r in rows:
        if r["protocol"] not in seen:
            seen.append(r["protocol"])
    known = [p for p in PROTOCOLS if p in seen]
    return known + [p for p in seen if p not in PROTOCOLS]


def by_protocol(rows, p):
    return sorted([r for r in rows if r["protocol"] == p], key=lambda r: num(r["control"]))


def save(fig, out, name, what):
    path = os.path.join(out, name)
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    log("wrote %s (%s)" % (path, what))


def control_value(p, c):
    """the control value with its symbol and unit, e.g. g_p = 6 or f = 0.5 Hz"""
    if p == "negative_g":
        return "$g_p$ = %s" % c
    if p == "rotating_g":
        return "$f$ = %s Hz" % c
    if not math.isfinite(num(c)):
        return "%s" % p if p else "series"
    return "control = %s" % c


# (protocol, control value) pairs that more than one run shares (an A/B comparison at one g_p):
# their legend entries name the run as well, or they could not be told apart
SHARED = set()


def run_value(r):
    """the run's control value for a legend, with the run's label where others share it"""
    if not math.isfinite(num(r["control"])):
        return r["label"]  # a series of unknown control is known by its label
    text = control_value(r["protocol"], r["control"])
    return "%s (%s)" % (text, r["label"]) if (r["protocol"], r["control"]) in SHARED else text


def label_of(r):
    if not r["protocol"]:
        return r["label"]
    return "%s, %s" % (protocol_name(r["protocol"]), run_value(r))


# ---- Fig. 4: time series ---------------------------------------------------------------------

def chart_series(d, out, max_series):
    series = read_csv(os.path.join(d, "series.csv"))
    summary = read_csv(os.path.join(d, "summary.csv"))
    if not series or not summary:
        log("skip fig4_series.png: no series.csv or summary.csv")
        return
    protos = protocols_in(summary)
    fig, axes = plt.subplots(len(protos), 1, figsize=(8, 3.2 * len(protos)), squeeze=False)
    for ax, p in zip(axes[:, 0], protos):
        runs = by_protocol(summary, p)
        # the lowest and highest control values, as in the paper, up to max_series runs
        pick = [runs[0], runs[-1]] if len(runs) > 1 else runs
        if max_series > 2 and len(runs) > 2:
            idx = np.linspace(0, len(runs) - 1, min(max_series, len(runs))).round().astype(int)
            pick = [runs[i] for i in sorted(set(idx))]
        for r in pick:
            pts = [s for s in series if s["label"] == r["label"]]
            tap = np.array([num(s["tap"]) for s in pts])
            phi = np.array([num(s["phi"]) for s in pts])
            used = np.array([s["used"] == "1" for s in pts])
            line = ax.plot(tap[used], phi[used], ".", ms=2, label=label_of(r))[0]
            ax.plot(tap[~used], phi[~used], "x", ms=3, color=line.get_color())
            ax.axhline(num(r["phi_mean"]), color=line.get_color(), lw=1.2)
        ax.set_title("%s: time series (x: discarded transient, line: mean)" % protocol_name(p))
        ax.set_xlabel("tap number")
        ax.set_ylabel(PHI)
        ax.legend(fontsize=8, markerscale=4)
    fig.tight_layout()
    save(fig, out, "fig4_series.png", "phi time series")


# ---- Figs 5-6: mean and sigma against the control parameter --------------------------------

def chart_mean_sigma(summary, out, p):
    rows = by_protocol(summary, p)
    if not rows:
        log("skip φ̄/σ chart for %s: no runs" % protocol_name(p))
        return
    c = np.array([num(r["control"]) for r in rows])
    # series of unknown control: one point per series, named by its label
    by_label = not np.all(np.isfinite(c))
    if by_label:
        c = np.arange(len(rows), dtype=float)
    m = np.array([num(r["phi_mean"]) for r in rows])
    mlo = np.array([num(r["phi_mean_lo_tau"]) for r in rows])
    mhi = np.array([num(r["phi_mean_hi_tau"]) for r in rows])
    s = np.array([num(r["sigma"]) for r in rows])
    slo = np.array([num(r["sigma_lo_tau"]) for r in rows])
    shi = np.array([num(r["sigma_hi_tau"]) for r in rows])
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 3.8))
    a.errorbar(c, m, yerr=[m - mlo, mhi - m], fmt="o-", capsize=3)
    a.set_xlabel(control_label(p))
    a.set_ylabel(r"mean volume fraction $\bar\phi$")
    a.set_title(r"(a) $\bar\phi$, 95 % CI ($\tau_{int}$-corrected)")
    b.errorbar(c, s, yerr=[s - slo, shi - s], fmt="s-", capsize=3, color="C3")
    b.set_xlabel(control_label(p))
    b.set_ylabel(r"standard deviation $\sigma_\phi$")
    b.set_title(r"(b) $\sigma_\phi$, 95 % $\chi^2$ CI ($\tau_{int}$-corrected)")
    if by_label:
        for ax in (a, b):
            ax.set_xticks(c, [r["label"] for r in rows], rotation=30, ha="right")
            ax.set_xlabel("series")
    fig.suptitle("%s protocol" % protocol_name(p) if p else r"$\bar\phi$ and $\sigma_\phi$ per series")
    fig.tight_layout()
    save(fig, out, "fig%s_mean_sigma_%s.png" % (FIGNUM.get(p, ("5", "7"))[0], p or "series"),
         "phi mean and sigma vs control, %s" % protocol_name(p))


# ---- Figs 7-8: KDEs, Q lines, β for two references ------------------------------------------

def chart_kde(kde, summary, out, p):
    rows = by_protocol(summary, p)
    if not rows:
        log("skip KDE chart for %s: no runs" % protocol_name(p))
        return
    fig, ax = plt.subplots(figsize=(7, 4))
    for r in rows:
        pts = [k for k in kde if k["label"] == r["label"]]
        ax.plot([num(k["phi"]) for k in pts], [num(k["p_normal"]) for k in pts],
                label=run_value(r))
    ax.set_xlabel(PHI)
    ax.set_ylabel(r"probability density $P(\phi)$")
    ax.set_title("%s: kernel density estimates (normal kernel, Silverman h)" % protocol_name(p))
    ax.legend(fontsize=7)
    save(fig, out, "fig%sa_kde_%s.png" % (FIGNUM.get(p, ("5", "7"))[1], p or "series"),
         "KDEs, %s" % protocol_name(p))


def chart_q(q, summary, ref, out, p):
    rows = [r for r in by_protocol(summary, p) if r["label"] != ref]
    if not rows:
        log("skip Q chart for %s: no runs besides the reference" % protocol_name(p))
        return
    fig, ax = plt.subplots(figsize=(7, 4.5))
    drawn = 0
    for r in rows:
        pts = [x for x in q if x["reference"] == ref and x["label"] == r["label"]]
        if not pts:
            continue
        drawn += 1
        x = np.array([num(v["inv_phi"]) for v in pts])
        y = np.array([num(v["q"]) for v in pts])
        e = np.array([num(v["q_err"]) for v in pts])
        fit = np.array([num(v["q_line"]) for v in pts])
        h = ax.errorbar(x, y, yerr=e, fmt="o", ms=3, capsize=2, label=label_of(r))
        if np.all(np.isfinite(fit)):
            ax.plot(x, fit, "-", color=h[0].get_color(), lw=1)
    if not drawn:
        plt.close(fig)
        log("skip Q chart for %s: no run overlaps the reference %s enough"
            % (protocol_name(p), ref))
        return
    ax.set_xlabel(r"inverse volume fraction $1/\phi$")
    ax.set_ylabel(r"$Q = \ln(P_1/P_0)$")
    ax.set_title("%s: overlapping histograms against %s (lines: binomial fits)" %
                 (protocol_name(p), ref))
    ax.legend(fontsize=7)
    save(fig, out, "fig%sb_q_%s.png" % (FIGNUM.get(p, ("5", "7"))[1], p), "Q lines, %s" % p)


def chart_two_refs(beta, summary, analysis, out, p):
    ref, ref2 = analysis.get("reference"), analysis.get("reference2")
    if not ref2:
        log("skip two-reference chart for %s: no second reference" % protocol_name(p))
        return
    rows = by_protocol(summary, p)
    if not rows:
        log("skip two-reference chart for %s: no runs" % protocol_name(p))
        return
    # only worth drawing when some run besides the references themselves has a β
    others = [b for b in beta if b["reference"] in (ref, ref2) and b["protocol"] == p
              and b["valid"] == "1" and b["label"] != b["reference"]]
    if not others:
        log("skip two-reference chart for %s: no run overlaps either reference enough"
            % protocol_name(p))
        return
    fig, ax = plt.subplots(figsize=(7, 4))
    off = num(analysis.get("reference_offset", {}).get("dbeta"))
    for k, (rl, mk) in enumerate(((ref, "s"), (ref2, "o"))):
        pts = [b for b in beta if b["reference"] == rl and b["protocol"] == p and b["valid"] == "1"]
        pts.sort(key=lambda b: num(b["control"]))
        c = [num(b["control"]) for b in pts]
        v = np.array([num(b["dbeta"]) for b in pts])
        e = [num(b["dbeta_err"]) for b in pts]
        ax.errorbar(c, v, yerr=e, fmt=mk, capsize=3, label=r"$\hat\beta$, reference %s" % rl)
        if k == 1 and math.isfinite(off):
            ax.plot(c, v + off, mk, mfc="none", ms=10, color="k",
                    label=r"reference %s shifted by %.0f m$^{-2}$" % (rl, off))
    ax.set_xlabel(control_label(p))
    ax.set_ylabel(r"relative inverse compactivity $\hat\beta$ (m$^{-2}$)")
    ax.set_title("%s: two references differ by a constant (P.39)" % protocol_name(p))
    ax.legend(fontsize=7)
    save(fig, out, "fig%sc_beta_refs_%s.png" % (FIGNUM.get(p, ("5", "7"))[1], p),
         "beta for two references, %s" % p)


# ---- Figs 9-11: quadron fit, ln Z, σ(φ̄) -----------------------------------------------------

def primary_rows(beta, analysis):
    ref = analysis.get("reference")
    return [b for b in beta if b["reference"] == ref and b["valid"] == "1"]


def chart_beta_phi(beta, quad, analysis, out):
    fits = (quad or {}).get("fits", {})
    allfit = fits.get("all")
    if not allfit or not allfit.get("converged"):
        log("skip fig9_beta_phi.png: no converged quadron fit")
        return
    b0 = allfit["beta0"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    rows = primary_rows(beta, analysis)
    for k, p in enumerate(protocols_in(rows)):
        pts = [b for b in rows if b["protocol"] == p]
        ax.errorbar([num(b["phi_mean"]) for b in pts], [num(b["dbeta"]) + b0 for b in pts],
                    xerr=[num(b["phi_err"]) for b in pts], yerr=[num(b["dbeta_err"]) for b in pts],
                    fmt="sdo^v"[k % 5], capsize=3, label=protocol_name(p))
    cv = allfit.get("curve")
    if cv:
        ax.plot(cv["phi"], np.array(cv["beta_hat"]) + b0, "k-",
                label=r"ideal quadron fit (P.26): $N\bar z/V_g$ = %.1f $\pm$ %.1f m$^{-2}$"
                % (allfit["a"], allfit["a_err"]))
    for name, f in fits.items():
        if name != "all" and f.get("converged") and f.get("curve"):
            ax.plot(f["curve"]["phi"], np.array(f["curve"]["beta_hat"]) + f["beta0"], "--",
                    lw=1, label="fit to %s only" % protocol_name(name))
    ax.set_xlabel(r"mean volume fraction $\bar\phi$")
    ax.set_ylabel(r"inverse compactivity $\beta = \hat\beta + \beta_0$ (m$^{-2}$)")
    ax.set_title(r"$\beta(\bar\phi)$ of all runs; $\beta_0$ = %.0f $\pm$ %.0f m$^{-2}$"
                 % (b0, allfit["beta0_err"]))
    ax.legend(fontsize=7)
    save(fig, out, "fig9_beta_phi.png", "beta vs phi with the quadron fit")


def chart_lnz(beta, quad, analysis, out):
    allfit = ((quad or {}).get("fits") or {}).get("all")
    if not allfit or not allfit.get("converged") or not allfit.get("curve"):
        log("skip fig10_lnz.png: no converged quadron fit")
        return
    b0 = allfit["beta0"]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    rows = primary_rows(beta, analysis)
    for k, p in enumerate(protocols_in(rows)):
        pts = [b for b in rows if b["protocol"] == p]
        ax.errorbar([num(b["dbeta"]) + b0 for b in pts], [num(b["dlnz"]) for b in pts],
                    yerr=[num(b["dlnz_err"]) for b in pts], fmt="sdo^v"[k % 5], capsize=3,
                    label=protocol_name(p))
    cv = allfit["curve"]
    ax.plot(np.array(cv["beta_hat"]) + b0, cv["dlnz"], "k-",
            label="ideal quadron (P.21), no further fit")
    ax.set_xlabel(BETA)
    ax.set_ylabel(r"$\ln Z(\beta) - \ln Z(\beta_{ref})$")
    ax.set_title("partition function from the intercepts (P.40)")
    ax.legend(fontsize=7)
    save(fig, out, "fig10_lnz.png", "ln Z vs beta with the quadron curve")


def chart_sigma_phi(summary, quad, out):
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for k, p in enumerate(protocols_in(summary)):
        rows = by_protocol(summary, p)
        s = np.array([num(r["sigma"]) for r in rows])
        ax.errorbar([num(r["phi_mean"]) for r in rows], s,
                    yerr=[s - np.array([num(r["sigma_lo_tau"]) for r in rows]),
                          np.array([num(r["sigma_hi_tau"]) for r in rows]) - s],
                    xerr=[num(r["phi_err"]) for r in rows], fmt="sdo^v"[k % 5], capsize=3,
                    label=protocol_name(p))
    allfit = ((quad or {}).get("fits") or {}).get("all")
    curve = bool(allfit and allfit.get("converged") and allfit.get("curve"))
    if curve:
        ax.plot(allfit["curve"]["phi"], allfit["curve"]["sigma_phi"], "k-",
                label="ideal quadron, (P.17) with (P.26)")
    elif quad is not None:
        log("fig11: no quadron curve (fit missing or not converged)")
    ax.set_xlabel(r"mean volume fraction $\bar\phi$")
    ax.set_ylabel(r"standard deviation $\sigma_\phi$")
    ax.set_title(r"fluctuations against the mean (95 % CIs)")
    ax.legend(fontsize=7)
    save(fig, out, "fig11_sigma_phi.png",
         "sigma vs phi" + (" with the quadron prediction" if curve else ""))


def chart_kernels(kde, analysis, out):
    ref = analysis.get("reference")
    pts = [k for k in kde if k["label"] == ref]
    if not pts:
        log("skip fig13_kernels.png: no KDE of the reference run")
        return
    x = [num(k["phi"]) for k in pts]
    fig, ax = plt.subplots(figsize=(7, 4))
    for col, name in (("p_normal", "normal"), ("p_epanechnikov", "Epanechnikov"), ("p_box", "box")):
        ax.plot(x, [num(k[col]) for k in pts], label="%s kernel" % name)
    ax.set_xlabel(PHI)
    ax.set_ylabel(r"probability density $P(\phi)$")
    ax.set_title("kernels compared on %s (normal h = %.2g, others equivalent)"
                 % (ref, num(pts[0]["bandwidth"])))
    ax.legend(fontsize=8)
    save(fig, out, "fig13_kernels.png", "KDE kernels compared")


def main(argv=None):
    """the command line (argv: its arguments; default sys.argv[1:])"""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("analysis_dir")
    ap.add_argument("--out", help="folder for the PNGs (default: the analysis folder)")
    ap.add_argument("--max-series", type=int, default=2,
                    help="runs per protocol in the time-series chart (default 2: lowest, highest)")
    a = ap.parse_args(argv)
    d = a.analysis_dir
    out = a.out or d
    os.makedirs(out, exist_ok=True)
    summary = read_csv(os.path.join(d, "summary.csv"))
    if not summary:
        log("no summary.csv in %s: nothing to chart" % d)
        return 1
    analysis = read_json(os.path.join(d, "analysis.json")) or {}
    # without a test area the analysis has no β̂: the charts of β and the quadron fit are left out
    has_beta = "beta.csv" in analysis.get("files", ["beta.csv"])
    if not has_beta:
        log("no test area: charts of the phi statistics only (no beta, no quadron fit)")
    quad = read_json(os.path.join(d, "quadron.json"), quiet=not has_beta)
    kde = read_csv(os.path.join(d, "kde.csv")) or []
    q = read_csv(os.path.join(d, "q_lines.csv"), quiet=not has_beta) or []
    beta = read_csv(os.path.join(d, "beta.csv"), quiet=not has_beta) or []
    ref = analysis.get("reference", "")
    keys = [(r["protocol"], r["control"]) for r in summary]
    SHARED.update(k for k in keys if keys.count(k) > 1)

    chart_series(d, out, a.max_series)
    # the protocols the data have, and nothing about the others
    for p in protocols_in(summary):
        chart_mean_sigma(summary, out, p)
        chart_kde(kde, summary, out, p)
        if has_beta:
            chart_q(q, summary, ref, out, p)
            chart_two_refs(beta, summary, analysis, out, p)
    if has_beta:
        chart_beta_phi(beta, quad, analysis, out)
        chart_lnz(beta, quad, analysis, out)
    chart_sigma_phi(summary, quad, out)
    chart_kernels(kde, analysis, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())

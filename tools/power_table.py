#!/usr/bin/env python3
"""The power of every claim's test against its source's alternative, by series length: the
tapping claims recomputed from a published report's analysis tables, their errors scaled as
1/√(taps), and the Random Force Model claims from a published report's shipped series, their
errors scaled as 1/√(sampled seconds). Writes docs/reproduction/power.md.

usage: power_table.py [REPORT_DIR] [OUT.md]   (defaults: docs/reproduction/tapping-standard,
                                               docs/reproduction/power.md; the RFM section from
                                               docs/reproduction/rfm-quick)
"""
import json
import math
import os
import shutil
import sys
import tempfile

# the gransim package of this source tree (its pure-Python part needs no build)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import numpy as np  # noqa: E402

LENGTHS = (50, 200, 1000, 2500, 10000)
SECONDS = (10, 40, 200, 1000)  # sampled seconds per run (the thesis' ring: 200–1000 s)


def table(folder, budget="standard", lengths=LENGTHS):
    """Markdown: one row per claim, its power at each series length (taps per value)"""
    from gransim.reproduce import tapping
    from gransim.reproduce.tapping_data import column
    with tempfile.TemporaryDirectory() as tmp:  # the claims draw charts: keep them out of folder
        shutil.copytree(os.path.join(folder, "analysis"), os.path.join(tmp, "analysis"))
        os.makedirs(os.path.join(tmp, "charts"))
        _, _, claims, _ = tapping.claims(tmp, budget)
        n_now = float(np.nanmedian(column(tapping.Study(tmp).runs(), "n_used")))
    name = os.path.basename(os.path.normpath(folder))
    lines = [f"# Power of each claim's test, by series length",
             "",
             f"Computed by `tools/power_table.py` from the analysis tables of `{name}` "
             f"(median {n_now:.0f} taps per value), every error scaled as 1/√(taps). Power is the "
             "probability that the claim's test detects the alternative its source names or shows "
             "(the *alternative* column, at the 5 % level); a claim *agrees* only where it is at "
             "least 0.80. `–`: the source sizes no alternative, or the shipped tables lack the "
             "series the test needs (per-tap series). one-curve, quadron-a and two-references use "
             "the bootstrap covariance of the β̂ across runs (analysis/beta_cov.csv) where it is "
             "shipped; without it their errors are taken as independent, the power shown is that "
             "of the independent test, and the claim cannot agree (gransim.reproduce.verdicts).",
             "",
             "| claim | alternative | " + " | ".join(f"{n} taps" for n in lengths) + " |",
             "|---|---|" + "---|" * len(lengths)]
    for c in claims:
        cells = []
        for n in lengths:
            p = c.power_at(n / n_now) if c.power_at else float("nan")
            cells.append(f"{p:.2f}" if p is not None and math.isfinite(p) else "–")
        alt = (c.alternative or "–").replace("|", "\\|")
        lines.append(f"| {c.id} | {alt} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


# the Random Force Model claims whose rules are functions of numbers alone: their power against
# the thesis' alternative δ when the measurement's error σ is δ/k (normal errors; a mean over
# three seeds' scatter, Student's t of 2 degrees of freedom, needs a smaller σ)
RFM_K = (1, 2, 3, 4, 8)


def rfm_rows():
    """(claim, alternative, k ↦ power or None)"""
    from gransim.reproduce import rfm_fluid as fl, rfm_models as mo
    src = [fl.ALPHA_PHI[p] for p in (0.088, 0.177, 0.353, 0.707)]
    vr, ratio = fl.CROSSOVER[(0.1, 0.1)]
    df = (6 - mo.SPM_ALPHA) / (6 - 3 * mo.SPM_ALPHA)  # eq. 5.29 inverted at α = 0.972
    return [
        ("g-R", "a level 0.01 off Fig. 4.7's 0.98 (twice its rounding)",
         lambda k: fl.gr_verdict(fl.GR_LEVEL, fl.GR_ALT / k).power),
        ("moments-phi", "none sized by the thesis", None),
        ("alpha-phi", "every φ = 0.088, 0.177, 0.353, 0.707 off by the tables' half-width δ there",
         lambda k: fl.alpha_phi_verdict([(a, h / k) for a, h in src], src).power),
        ("crossover", "v_r 0.009 or v_c/v_r 0.016 off Table 5.3's ε = 0.1 row (the step to the next "
         "row; σ of each δ/k)",
         lambda k: fl.crossover_verdict(vr, 0.009 / k, ratio, 0.016 / k).power),
        ("spm-alpha", "α 0.06 off eq. 5.29's 0.972 (twice its ± 0.03)",
         lambda k: mo.spm_verdict(df, 2 * mo.SPM_TOL / k / mo.dalpha(df))[2].power),
        ("spm-pv", "none sized by the thesis (\"remarkably good over many decades\")", None),
        ("cascade", "one process 2 × its Table 6.2 ± off (σ of each δ/k)",
         lambda k: mo.cascade_verdict({n: (s, 2 * t / k, None)
                                       for n, (s, t) in mo.TABLE_6_2.items()}).power),
    ]


def rfm_section(ks=RFM_K):
    """Markdown: the RFM claims' power by the measurement's error relative to the alternative"""
    lines = ["",
             "## Random Force Model: power by the measurement's error",
             "",
             "For the 2D-fluid and model claims, whose runs the quick report lacks: each claim's "
             "power against the thesis' alternative δ when its "
             "measurement's standard error σ is δ/k (normal errors, from the rules in "
             "gransim.reproduce.rfm_fluid and rfm_models; a claim's σ falls as 1/√(seconds "
             "sampled × seeds), and a mean over three seeds judged on their scatter, Student's t of "
             "2 degrees of freedom, needs a smaller σ for the same power). `–`: the thesis sizes no "
             "alternative, so the claim can disagree but never agree.",
             "",
             "| claim | alternative δ | " + " | ".join(f"σ = δ/{k}" for k in ks) + " |",
             "|---|---|" + "---|" * len(ks)]
    for cid, alt, power in rfm_rows():
        cells = [f"{power(k):.2f}" if power else "–" for k in ks]
        lines.append(f"| {cid} | {alt} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def _sampled(d, sweep):
    """the shortest sampled time (t_end − t_steady, s) of a sweep's runs, from their rfm.json"""
    base = os.path.join(d, "analysis", sweep)
    out = []
    for run in sorted(os.listdir(base)) if os.path.isdir(base) else []:
        p = os.path.join(base, run, "rfm.json")
        if os.path.exists(p):
            with open(p) as f:
                i = json.load(f)
            out.append(float(i.get("t_end", math.nan)) - float(i.get("t_steady", math.nan)))
    return min(out) if out else math.nan


def rfm_table(folder, lengths=SECONDS):
    """Markdown: the Random Force Model claims' power at each sampled time per run, from the
    series a report folder ships (report.json)"""
    from gransim.reproduce import rfm, series
    from gransim.reproduce.rfm_conditions import sweep_for
    with open(os.path.join(folder, "report.json")) as f:
        info = json.load(f)
    name = os.path.basename(os.path.normpath(folder))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:  # the claims draw charts: keep them out of folder
        series.unpack(folder, info, tmp)
        os.makedirs(os.path.join(tmp, "charts"), exist_ok=True)
        _, _, claims, _ = rfm.claims(tmp, info["budget"])
        for c in claims:
            now = _sampled(tmp, sweep_for(tmp, c.id, rfm.SWEEP[c.id]))
            cells = []
            for s in lengths:
                p = c.power_at(s / now) if c.power_at and math.isfinite(now) else float("nan")
                cells.append(f"{p:.2f}" if p is not None and math.isfinite(p) else "–")
            alt = (c.alternative or "–").replace("|", "\\|")
            now_text = f"{now:.3g} s" if math.isfinite(now) else "–"
            rows.append(f"| {c.id} | {alt} | {now_text} | " + " | ".join(cells) + " |")
    return "\n".join([
        "## Random Force Model",
        "",
        f"Computed by `tools/power_table.py` from the series shipped with `{name}`, every error "
        "scaled as 1/√(sampled seconds per run) from the time each claim's runs sampled (the "
        "*sampled* column). `–`: the source sizes no alternative, the report has none of the "
        "claim's runs yet, or the claim's verdict gives its power at the runs' own length only.",
        "",
        "| claim | alternative | sampled | " + " | ".join(f"{n} s" for n in lengths) + " |",
        "|---|---|---|" + "---|" * len(lengths)] + rows) + "\n"


def document(root):
    """power.md: the tapping table, then the Random Force Model's"""
    return (table(os.path.join(root, "tapping-standard")) + "\n"
            + rfm_table(os.path.join(root, "rfm-quick")) + rfm_section())


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "reproduction")
    folder = argv[0] if argv else os.path.join(root, "tapping-standard")
    out = argv[1] if len(argv) > 1 else os.path.join(root, "power.md")
    if not os.path.isfile(os.path.join(folder, "analysis", "summary.csv")):
        sys.exit(f"power_table: {folder}/analysis/summary.csv: no analysis tables here")
    text = table(folder) + "\n" + rfm_table(os.path.join(root, "rfm-quick")) + rfm_section()
    with open(out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()

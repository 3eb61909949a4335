#!/usr/bin/env python3
"""The power of every claim's test against its source's alternative, by series length: the
tapping claims recomputed from a published report's analysis tables, their errors scaled as
1/√(taps). Writes docs/reproduction/power.md.

usage: power_table.py [REPORT_DIR] [OUT.md]   (defaults: docs/reproduction/tapping-standard,
                                               docs/reproduction/power.md)
"""
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


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "reproduction")
    folder = argv[0] if argv else os.path.join(root, "tapping-standard")
    out = argv[1] if len(argv) > 1 else os.path.join(root, "power.md")
    if not os.path.isfile(os.path.join(folder, "analysis", "summary.csv")):
        sys.exit(f"power_table: {folder}/analysis/summary.csv: no analysis tables here")
    text = table(folder)
    with open(out, "w") as f:
        f.write(text)


if __name__ == "__main__":
    main()

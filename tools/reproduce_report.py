#!/usr/bin/env python3
"""Write the report of `gransim reproduce`: DIR/report.md, DIR/report.html, DIR/claims.csv and
the claim charts in DIR/charts/, from the analysis in DIR/analysis and the runs in DIR/sweeps.

usage: reproduce_report.py --study tapping|rfm --budget B [--wall S] [--cores N]
                           [--command TEXT] DIR
"""
import argparse
import datetime
import glob
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "reproduce"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")

import report  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--study", required=True, choices=["tapping", "rfm"])
    ap.add_argument("--budget", required=True)
    ap.add_argument("--wall", type=float, default=float("nan"), help="wall seconds in all")
    ap.add_argument("--cores", type=int, default=os.cpu_count())
    ap.add_argument("--command", default="")
    a = ap.parse_args()
    if not os.path.isdir(os.path.join(a.dir, "analysis")):
        sys.exit(f"reproduce_report: {a.dir}/analysis: no analysis here (run gransim reproduce)")
    os.makedirs(os.path.join(a.dir, "charts"), exist_ok=True)
    if a.study == "tapping":
        import tapping as study
    else:
        import rfm as study
    title, intro, claims, notes = study.claims(a.dir, a.budget)
    hours = a.wall / 3600.0
    # the runs' own wall times (one thread each): the cost whatever the sittings were
    core_s, runs = 0.0, 0
    for sweep in sorted(glob.glob(os.path.join(a.dir, "sweeps", "*", "*", "run.json"))):
        try:
            with open(sweep) as f:
                core_s += float(json.load(f).get("wall_time_s", 0.0))
            runs += 1
        except (OSError, ValueError):
            pass
    meta = [("study", a.study), ("budget", a.budget),
            ("command", a.command or f"gransim reproduce {a.study} --budget {a.budget}"),
            ("machine", report.machine()),
            ("wall time", f"{a.wall:.0f} s ({hours:.2f} h) of `gransim reproduce` on {a.cores} "
                          "cores, all sittings"),
            ("run time", f"{core_s / 3600:.2f} core-hours: the wall times of its {runs} runs "
                         "(one thread each) added up"),
            ("written", datetime.datetime.now().strftime("%Y-%m-%d %H:%M"))]
    report.write_report(a.dir, title, intro, meta, claims, notes)
    print(f"reproduce_report: {len(claims)} claims → {a.dir}/report.md, report.html, claims.csv")


if __name__ == "__main__":
    main()

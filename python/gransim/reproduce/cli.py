"""Write the report of `gransim reproduce`: DIR/report.md, DIR/report.html, DIR/claims.csv and
the claim charts in DIR/charts/, from the analysis in DIR/analysis and the runs in DIR/sweeps;
DIR/series/ and DIR/report.json keep every file the verdicts read. With --from-series, the
report is written again from DIR/series and DIR/report.json alone (a published report).

usage: python3 -m gransim.reproduce --study tapping|rfm --budget B [--wall S] [--cores N]
                                    [--command TEXT] [--from-series] DIR
"""
import argparse
import csv
import datetime
import glob
import json
import math
import os
import shutil
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")

from . import described  # noqa: E402
from . import report  # noqa: E402
from . import series  # noqa: E402


def planned_runs(folder):
    """how many runs plan.json asks for (each sweep: the product of its parameters' values)"""
    try:
        with open(os.path.join(folder, "plan.json")) as f:
            plan = json.load(f)
    except (OSError, ValueError):
        return 0
    total = 0
    for sw in plan.get("sweeps", []):
        n = 1
        for p in sw.get("params", []):
            n *= len(p.split("=", 1)[1].split(","))
        total += n
    return total


def study_claims(study, folder, budget):
    """the study's claims, and what its runs are: a plan that resolves nothing gives no verdict
    (every claim not resolved, saying why); facts: the runs' own pile for the departures table"""
    mod = study_module(study)
    title, intro, claims, notes = mod.claims(folder, budget)
    resolves, purpose = described.plan_resolves(described.plan(folder))
    if not resolves:
        described.without_verdicts(claims, budget, purpose)
    facts = mod.departure_facts(folder) if hasattr(mod, "departure_facts") else None
    return title, intro, claims, notes, facts


def study_module(name):
    if name == "tapping":
        from . import tapping as study
    else:
        from . import rfm as study
    return study


def from_series(a):
    """the report again from DIR/series and DIR/report.json, in a scratch folder whose relative
    run paths the shipped tables name; report.md, report.html, claims.csv and charts back in DIR"""
    info = series.load(a.dir, a.study, a.budget)
    tmp = tempfile.mkdtemp(prefix="gs-report-")
    here = os.getcwd()
    try:
        series.unpack(a.dir, info, tmp)
        os.makedirs(os.path.join(tmp, "charts"))
        os.chdir(tmp)
        title, intro, claims, notes, facts = study_claims(a.study, tmp, a.budget)
        report.write_report(tmp, title, intro, [tuple(m) for m in info["meta"]], claims, notes,
                            a.study, facts)
        os.chdir(here)
        os.makedirs(os.path.join(a.dir, "charts"), exist_ok=True)
        for f in ("report.md", "report.html", "claims.csv"):
            shutil.copy2(os.path.join(tmp, f), os.path.join(a.dir, f))
        for png in glob.glob(os.path.join(tmp, "charts", "*.png")):
            shutil.copy2(png, os.path.join(a.dir, "charts"))
    finally:
        os.chdir(here)
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"reproduce_report: {len(claims)} claims from {a.dir}/series → {a.dir}/report.md, "
          "report.html, claims.csv")


def run_time_text(core_s, runs, by_wall):
    """the header's run time: the runs' CPU times, naming those counted by wall time"""
    if runs and by_wall == runs:
        how = (f"the wall times of its {runs} runs added up (none kept its CPU time), which "
               "count what else ran beside them")
    else:
        how = f"the CPU times of its {runs} runs (one thread each) added up" + (
            f"; {by_wall} of them by their wall times (no CPU time kept for every session), "
            "which count what else ran beside them" if by_wall else "")
    return f"{core_s / 3600:.2f} core-hours: {how}"


def run_cost(folder):
    """the runs' cost: (core-seconds, runs, runs counted by wall time, unfinished runs). A run
    counts its CPU time (one thread each: the cost whatever the sittings were and whatever else
    the machine ran) when its run.json keeps it for every session, else its wall time"""
    core_s, runs, by_wall, unfinished = 0.0, 0, 0, []
    taps = {}  # the taps each run has written, as the analysis counted them
    try:
        with open(os.path.join(folder, "analysis", "runs.csv"), newline="") as f:
            taps = {os.path.realpath(r["dir"]): r["taps"] for r in csv.DictReader(f)}
    except (OSError, KeyError):
        pass
    for path in sorted(glob.glob(os.path.join(folder, "sweeps", "*", "*", "run.json"))):
        try:
            with open(path) as f:
                rj = json.load(f)
            if "cpu_time_s" in rj and rj.get("cpu_time_sessions") == rj.get("sessions"):
                core_s += float(rj["cpu_time_s"])
            else:
                core_s += float(rj.get("wall_time_s", 0.0))
                by_wall += 1
            runs += 1
            if rj.get("status") != "completed":
                name = os.path.relpath(os.path.dirname(path), os.path.join(folder, "sweeps"))
                n = taps.get(os.path.realpath(os.path.dirname(path)), rj.get("taps_done"))
                done = f": {n} of {rj['taps_requested']} taps" if "taps_requested" in rj else ""
                unfinished.append(f"{name}{done}")
        except (OSError, ValueError, KeyError):
            pass
    return core_s, runs, by_wall, unfinished


def main(argv=None):
    """the command line (argv: its arguments; default sys.argv[1:])"""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--study", required=True, choices=["tapping", "rfm"])
    ap.add_argument("--budget", required=True)
    ap.add_argument("--wall", type=float, default=float("nan"), help="wall seconds in all")
    ap.add_argument("--cores", type=int, default=os.cpu_count())
    ap.add_argument("--command", default="")
    ap.add_argument("--from-series", action="store_true",
                    help="write the report again from DIR/series and DIR/report.json")
    a = ap.parse_args(argv)
    if a.from_series:
        return from_series(a)
    if not os.path.isdir(os.path.join(a.dir, "analysis")):
        sys.exit(f"reproduce_report: {a.dir}/analysis: no analysis here (run gransim reproduce)")
    os.makedirs(os.path.join(a.dir, "charts"), exist_ok=True)
    reads = series.record_reads(a.dir)
    title, intro, claims, notes, facts = study_claims(a.study, a.dir, a.budget)
    inputs = set(reads)  # what the verdicts read; the header's bookkeeping below is not shipped
    hours = a.wall / 3600.0
    core_s, runs, by_wall, unfinished = run_cost(a.dir)
    # sittings of `reproduce` that cannot have run half of the runs' cost did not make them
    tallied = not math.isfinite(a.wall) or a.wall * a.cores >= 0.5 * core_s
    command = a.command or f"gransim reproduce {a.study} --budget {a.budget}"
    meta = [("study", a.study), ("budget", a.budget),
            ("command", f"`{command}` (runs, analysis and report in "
                        f"runs/reproduce-{a.study}-{a.budget} unless --out DIR is given)"),
            ("series", "series/ holds every file the verdicts read (the analysis tables and "
                       "each run's per-tap or per-sample series, gzipped); "
                       f"`gransim reproduce {a.study} --budget {a.budget} --out DIR "
                       "--from-series` writes this report and claims.csv again from them alone, "
                       "DIR being this report's folder"),
            ("machine", report.machine()),
            ("wall time", f"{a.wall:.0f} s ({hours:.2f} h) of `gransim reproduce` on {a.cores} "
                          "cores, all sittings" if tallied else
                          f"not tallied ({a.wall:.0f} s): most runs were made outside `gransim "
                          "reproduce` (by `gransim sweep` into its folders) and adopted; the run "
                          "time below is their cost"),
            ("run time", run_time_text(core_s, runs, by_wall)),
            ("written", datetime.datetime.now().strftime("%Y-%m-%d %H:%M"))]
    planned = planned_runs(a.dir)
    if unfinished or (planned and runs < planned):
        unit = "taps" if a.study == "tapping" else "samples"
        meta.append(("in progress", f"{runs - len(unfinished)} of {planned or '?'} planned runs "
                     f"complete; this report covers the {unit} there are so far"
                     + ("; under way: " + "; ".join(unfinished) if unfinished else "")))
    report.write_report(a.dir, title, intro, meta, claims, notes, a.study, facts)
    series.write(a.dir, a.study, a.budget, meta, inputs)
    print(f"reproduce_report: {len(claims)} claims → {a.dir}/report.md, report.html, claims.csv")


if __name__ == "__main__":
    main()

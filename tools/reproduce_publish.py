#!/usr/bin/env python3
"""Copy a reproduction's report into the repository's docs: report.md, report.html, claims.csv,
plan.json, progress.json, the claim charts, the analysis' summary tables and the series the
verdicts read (series/, report.json: `gransim reproduce … --from-series` writes the report again
from them); no raw runs.

usage: reproduce_publish.py RUN_DIR DOCS_DIR      (e.g. runs/reproduce-tapping-quick
                                                   docs/reproduction/tapping-quick)"""
import glob
import gzip
import json
import os
import re
import shutil
import sys

SUMMARIES = ["summary.csv", "beta.csv", "beta_multi.csv", "beta_cov.csv", "pairs.csv",
             "quadron.json", "analysis.json", "runs.csv", "rfm_summary.json", "exponents.csv",
             "moments_vs_N.csv"]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, dst = sys.argv[1], sys.argv[2]
    if not os.path.exists(os.path.join(src, "report.md")):
        sys.exit(f"reproduce_publish: {src} has no report.md (run gransim reproduce first)")
    if os.path.isdir(dst):
        shutil.rmtree(dst)
    os.makedirs(os.path.join(dst, "charts"))
    if not os.path.exists(os.path.join(src, "report.json")):
        sys.exit(f"reproduce_publish: {src} has no report.json and series/ (written by gransim "
                 "reproduce: make the report again with --report-only)")
    for f in ("report.md", "report.html", "claims.csv", "plan.json", "progress.json",
              "report.json"):
        if os.path.exists(os.path.join(src, f)):
            shutil.copy2(os.path.join(src, f), dst)
    shutil.copytree(os.path.join(src, "series"), os.path.join(dst, "series"))
    for png in glob.glob(os.path.join(src, "charts", "*.png")):
        shutil.copy2(png, os.path.join(dst, "charts"))
    # the plan's command as a reader types it: where this machine put the runs is not part of it
    plan = os.path.join(dst, "plan.json")
    if os.path.exists(plan):
        with open(plan) as f:
            p = json.load(f)
        p["command"] = re.sub(r" --out \S+| --out '[^']*'", "", p.get("command", ""))
        with open(plan, "w") as f:
            f.write(json.dumps(p, indent=2, ensure_ascii=False) + "\n")
    # the analysis' summary tables, folder by folder (RFM: one per sweep); where the series
    # hold a table, its copy there, whose paths the report already made relative to the folder
    # it was written in (that folder may since have been copied elsewhere)
    for path in glob.glob(os.path.join(src, "analysis", "**", "*"), recursive=True):
        if os.path.basename(path) in SUMMARIES:
            rel = os.path.relpath(path, src)
            os.makedirs(os.path.join(dst, os.path.dirname(rel)), exist_ok=True)
            shipped = os.path.join(src, "series", rel + ".gz")
            if os.path.exists(shipped):
                with gzip.open(shipped, "rb") as z, open(os.path.join(dst, rel), "wb") as f:
                    shutil.copyfileobj(z, f)
            else:
                shutil.copy2(path, os.path.join(dst, rel))
    # run directories are local paths of the machine that ran them: keep them relative to the
    # reproduction folder (the command line in the report stays as it was typed)
    for path in glob.glob(os.path.join(dst, "analysis", "**", "*"), recursive=True):
        if path.endswith((".csv", ".json")):
            with open(path) as f:
                text = f.read()
            with open(path, "w") as f:
                f.write(text.replace(os.path.abspath(src) + "/", ""))
    size = sum(os.path.getsize(os.path.join(d, f)) for d, _, fs in os.walk(dst) for f in fs)
    ser = sum(os.path.getsize(os.path.join(d, f))
              for d, _, fs in os.walk(os.path.join(dst, "series")) for f in fs)
    print(f"reproduce_publish: {src} → {dst} ({size / 1024:.0f} kB, of which series/ "
          f"{ser / 1024:.0f} kB)")
    # a report folder is meant to stay a few MB: name the largest series when it does not
    if size > 5 * 1024 ** 2:
        big = sorted(((os.path.getsize(os.path.join(d, f)), os.path.relpath(os.path.join(d, f), dst))
                      for d, _, fs in os.walk(os.path.join(dst, "series")) for f in fs),
                     reverse=True)[:5]
        print(f"reproduce_publish: warning: {dst} holds {size / 1024 ** 2:.1f} MB; the largest "
              "series: " + ", ".join(f"{p} ({n / 1024:.0f} kB)" for n, p in big))


if __name__ == "__main__":
    main()

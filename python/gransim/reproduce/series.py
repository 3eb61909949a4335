"""The series a report ships: every file its verdicts read (the analysis tables and the runs'
per-tap or per-sample series), gzipped into DIR/series/ with DIR's own path taken out, and
DIR/report.json (the header and the list of those files). From them alone the report and
claims.csv can be written again, identical (`python3 -m gransim.reproduce --from-series`)."""
import gzip
import json
import os
import shutil
import sys

# what a report writes: never an input of its own
OUTPUTS = ("report.md", "report.html", "claims.csv", "report.json")
OUT_DIRS = ("charts", "series")


def record_reads(folder):
    """the set (filled as the report runs) of files under folder opened for reading, relative to
    folder; an audit hook sees every open, whoever makes it (csv, json, numpy)"""
    roots = {os.path.abspath(folder), os.path.realpath(folder)}
    seen = set()

    def hook(event, args):
        if event != "open" or not isinstance(args[0], (str, bytes, os.PathLike)):
            return
        mode, flags = args[1], args[2]
        if isinstance(mode, str) and any(c in mode for c in "wax+"):
            return
        if mode is None and isinstance(flags, int) and flags & (os.O_WRONLY | os.O_RDWR):
            return
        path = os.path.abspath(os.fsdecode(args[0]))
        for root in roots:
            if path.startswith(root + os.sep):
                rel = os.path.relpath(path, root)
                if rel not in OUTPUTS and rel.split(os.sep)[0] not in OUT_DIRS:
                    seen.add(rel)
                return

    sys.addaudithook(hook)
    return seen


def _prefixes(folder):
    """the spellings of folder that its files may hold, longest first"""
    ps = {os.path.abspath(folder), os.path.realpath(folder)}
    if not os.path.isabs(folder):
        ps.add(os.path.normpath(folder))
    return sorted((p.rstrip(os.sep) + os.sep for p in ps if p not in (".", os.sep)),
                  key=len, reverse=True)


def write(folder, study, budget, meta, inputs):
    """DIR/series/<input>.gz for every input (DIR's path made relative) and DIR/report.json"""
    out = os.path.join(folder, "series")
    shutil.rmtree(out, ignore_errors=True)
    prefixes = [p.encode() for p in _prefixes(folder)]
    for rel in sorted(inputs):
        with open(os.path.join(folder, rel), "rb") as f:
            data = f.read()
        for p in prefixes:
            data = data.replace(p, b"")
        dst = os.path.join(out, rel + ".gz")
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        # no name, no time stamp: the same data gives the same bytes
        with open(dst, "wb") as raw, gzip.GzipFile(filename="", mode="wb", fileobj=raw,
                                                   compresslevel=9, mtime=0) as z:
            z.write(data)
    info = {"study": study, "budget": budget, "meta": [list(m) for m in meta],
            "inputs": sorted(inputs)}
    with open(os.path.join(folder, "report.json"), "w") as f:
        json.dump(info, f, indent=1, ensure_ascii=False)
        f.write("\n")


def load(folder, study, budget):
    """report.json of a report folder, checked against the study and budget asked for"""
    path = os.path.join(folder, "report.json")
    if not os.path.exists(path):
        raise SystemExit(f"reproduce_report: {path} is missing: {folder} is not a report "
                         "shipped with its series (written by gransim reproduce)")
    try:
        with open(path) as f:
            info = json.load(f)
        ok = isinstance(info["meta"], list) and isinstance(info["inputs"], list)
    except (OSError, ValueError, KeyError, TypeError) as e:
        raise SystemExit(f"reproduce_report: {path}: not a report's series list ({e})")
    if not ok:
        raise SystemExit(f"reproduce_report: {path}: meta and inputs must be lists")
    if (info.get("study"), info.get("budget")) != (study, budget):
        raise SystemExit(f"reproduce_report: {path} is the report of {info.get('study')} at "
                         f"the {info.get('budget')} budget, not {study} at {budget}")
    return info


def unpack(folder, info, dst):
    """the inputs of a shipped report, ungzipped into dst in their original layout"""
    for rel in info["inputs"]:
        if os.path.isabs(rel) or rel.startswith(".."):
            raise SystemExit(f"reproduce_report: {folder}/report.json: input {rel!r} is not "
                             "inside the report folder")
        src = os.path.join(folder, "series", rel + ".gz")
        if not os.path.exists(src):
            raise SystemExit(f"reproduce_report: {src} is missing (the report reads it)")
        os.makedirs(os.path.dirname(os.path.join(dst, rel)), exist_ok=True)
        with gzip.open(src, "rb") as z, open(os.path.join(dst, rel), "wb") as f:
            shutil.copyfileobj(z, f)

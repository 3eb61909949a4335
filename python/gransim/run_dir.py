"""Reading a gransim run directory (or an analysis or sweep folder) into pandas DataFrames."""

import io
import json
import os

__all__ = ["read_csv", "read_run"]


def read_csv(path):
    """one gransim CSV file as a DataFrame. Accepts both forms: preamble lines starting with
    '#' (metadata, skipped) before the header, and plain CSV. '# key=value' preamble lines are
    kept in the DataFrame's .attrs["meta"]."""
    import pandas as pd

    meta = {}
    body = []
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                text = line[1:].strip()
                if "=" in text:
                    k, v = text.split("=", 1)
                    meta[k.strip()] = v.strip()
                continue
            if line.strip():
                body.append(line)
    if not body:
        df = pd.DataFrame()
    else:
        df = pd.read_csv(io.StringIO("".join(body)))
    df.attrs["meta"] = meta
    df.attrs["path"] = str(path)
    return df


def read_run(path):
    """every CSV file of a run directory as a DataFrame keyed by its name without '.csv'
    ("taps", "series", …; files in sub-folders as "folder/name"), and run.json (or any other
    .json file) parsed, keyed by its file name ("run.json")."""
    path = os.fspath(path)
    if not os.path.isdir(path):
        raise FileNotFoundError(f"{path}: not a run directory")
    out = {}
    for root, dirs, files in os.walk(path):
        dirs.sort()
        # frames/ holds only pictures; skip it quickly
        dirs[:] = [d for d in dirs if d != "frames"]
        rel = os.path.relpath(root, path)
        for name in sorted(files):
            full = os.path.join(root, name)
            key = name if rel == "." else f"{rel}/{name}"
            if name.endswith(".csv"):
                out[key[: -len(".csv")]] = read_csv(full)
            elif name.endswith(".json"):
                with open(full, encoding="utf-8") as f:
                    out[key] = json.load(f)
    return out

"""Reading a gransim run directory (or an analysis or sweep folder) into pandas DataFrames."""

import errno
import io
import json
import os
from collections.abc import Mapping

__all__ = ["RunFiles", "read_csv", "read_run"]


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


class RunFiles(Mapping):
    """a run directory's files by name, each read when it is first looked up and kept: a
    snapshot folder of many contact files costs nothing until one of them is used"""

    def __init__(self, path, files):
        self.path = path
        self._files = files  # key → full path, in walk order
        self._loaded = {}

    def __getitem__(self, key):
        if key not in self._loaded:
            full = self._files[key]  # KeyError for a name the run does not have
            if full.endswith(".csv"):
                self._loaded[key] = read_csv(full)
            else:
                with open(full, encoding="utf-8") as f:
                    self._loaded[key] = json.load(f)
        return self._loaded[key]

    def __contains__(self, key):
        return key in self._files  # without reading the file

    def __iter__(self):
        return iter(self._files)

    def __len__(self):
        return len(self._files)

    def loaded(self):
        """the names read so far"""
        return list(self._loaded)

    def __repr__(self):
        return f"<gransim run {self.path}: {len(self)} files, {len(self._loaded)} read>"


def read_run(path):
    """every CSV file of a run directory as a DataFrame keyed by its name without '.csv'
    ("taps", "series", …; files in sub-folders as "folder/name"), and run.json (or any other
    .json file) parsed, keyed by its file name ("run.json"). A mapping that reads each file
    when it is first looked up (dict(run) reads them all)."""
    path = os.fspath(path)
    if not os.path.isdir(path):
        raise FileNotFoundError(errno.ENOENT, "not a run directory", path)
    files = {}
    for root, dirs, names in os.walk(path):
        dirs.sort()
        # frames/ holds only pictures; skip it quickly
        dirs[:] = [d for d in dirs if d != "frames"]
        rel = os.path.relpath(root, path)
        for name in sorted(names):
            key = name if rel == "." else f"{rel}/{name}"
            if name.endswith(".csv"):
                files[key[: -len(".csv")]] = os.path.join(root, name)
            elif name.endswith(".json"):
                files[key] = os.path.join(root, name)
    return RunFiles(path, files)

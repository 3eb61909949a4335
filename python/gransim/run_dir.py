"""Reading a gransim run directory (or an analysis or sweep folder) into pandas DataFrames."""

import errno
import io
import json
import os
from collections.abc import Mapping

__all__ = ["H5mdTrajectory", "RunFiles", "read_csv", "read_run"]


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


class H5mdTrajectory:
    """an H5MD trajectory (a run's trajectory.h5md) opened with h5py and read lazily: the
    attributes are h5py datasets, so that `positions[k]` reads frame k alone and nothing is
    loaded up front. Shapes: positions and velocities F×N×3 (m, m/s; z = 0), theta and omega
    F×N (rad, rad/s), contacts F×N, time F (s), step F, box F×3×3 (m, the edges on the
    diagonal), gravity F×3 (m/s²), tap F (−1 outside taps); fixed in time: species N (indices
    into species_names), radius N (m), ids N, sides N (0 for disks)."""

    def __init__(self, path):
        """open the file at `path` read-only (h5py); FileNotFoundError when there is none"""
        import h5py

        if not os.path.isfile(os.fspath(path)):
            raise FileNotFoundError(errno.ENOENT, "no H5MD trajectory", os.fspath(path))

        self.path = os.fspath(path)
        self.file = h5py.File(self.path, "r")
        p = self.file["particles/all"]
        self.positions = p["position/value"]
        self.velocities = p["velocity/value"]
        self.theta = p["theta/value"]
        self.omega = p["omega/value"]
        self.contacts = p["contacts/value"]
        self.time = p["position/time"]
        self.step = p["position/step"]
        self.box = p["box/edges/value"]
        self.gravity = self.file["observables/gravity/value"]
        self.tap = self.file["observables/tap/value"]
        self.species = p["species"]
        self.radius = p["radius"]
        self.ids = p["id"]
        self.sides = p["sides"]
        self.species_names = [n.decode() if isinstance(n, bytes) else str(n)
                              for n in p["species"].attrs["names"]]

    def __len__(self):
        return self.positions.shape[0]

    def frame(self, k):
        """frame k as a DataFrame, one row per grain in label order (id, species, x, y, vx, vy,
        theta, omega, radius, contacts); its time, step and box lengths in .attrs"""
        import pandas as pd

        if not -len(self) <= k < len(self):
            raise IndexError(f"frame {k} of a trajectory of {len(self)} frames")
        pos, vel = self.positions[k], self.velocities[k]
        names = self.species_names
        df = pd.DataFrame({
            "id": self.ids[()], "species": [names[s] for s in self.species[()]],
            "x": pos[:, 0], "y": pos[:, 1], "vx": vel[:, 0], "vy": vel[:, 1],
            "theta": self.theta[k], "omega": self.omega[k], "radius": self.radius[()],
            "contacts": self.contacts[k]})
        box = self.box[k]
        df.attrs.update(t=float(self.time[k]), step=int(self.step[k]),
                        box=(float(box[0, 0]), float(box[1, 1])))
        return df

    def close(self):
        self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *args):
        self.close()

    def __repr__(self):
        return f"<H5MD trajectory {self.path}: {len(self)} frames of {self.positions.shape[1]} grains>"


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
            elif full.endswith((".h5md", ".h5")):
                self._loaded[key] = H5mdTrajectory(full)
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
    .json file) parsed, keyed by its file name ("run.json"); an H5MD trajectory
    ("trajectory.h5md") as an H5mdTrajectory whose arrays are read frame by frame. A mapping
    that reads each file when it is first looked up (dict(run) reads them all)."""
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
            elif name.endswith((".json", ".h5md", ".h5")):
                files[key] = os.path.join(root, name)
    return RunFiles(path, files)

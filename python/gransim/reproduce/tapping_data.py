"""Reading a tapping reproduction: the analysis files of `gransim analyze` and the runs' own
taps.csv and segregation.csv, the ideal-quadron formulas (P.17, P.26) the claims need, and the
helpers that draw the claims' charts."""
import csv
import json
import math
import os

import matplotlib.pyplot as plt
import numpy as np

from .batch import batch_err


def read_csv(path):
    """rows of a CSV as dicts of floats where the text is a number"""
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        rows = []
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            d = {}
            for k, v in r.items():
                try:
                    d[k] = float(v)
                except (TypeError, ValueError):
                    d[k] = v
            rows.append(d)
        return rows


def read_json(path):
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return json.load(f)


def column(rows, key):
    return np.array([r.get(key, float("nan")) for r in rows], float)


class Study:
    """everything a tapping report reads, by run label"""

    def __init__(self, folder):
        a = os.path.join(folder, "analysis")
        self.folder = folder
        self.summary = read_csv(os.path.join(a, "summary.csv"))
        self.beta = read_csv(os.path.join(a, "beta.csv"))
        self.beta_multi = read_csv(os.path.join(a, "beta_multi.csv"))
        self.q_lines = read_csv(os.path.join(a, "q_lines.csv"))
        self.quadron = read_json(os.path.join(a, "quadron.json"))
        self.info = read_json(os.path.join(a, "analysis.json"))
        self.discard = int(self.info.get("discard", 10))
        self._cov = read_csv(os.path.join(a, "beta_cov.csv"))
        self.replicas = int(self.info.get("bootstrap_replicas") or 0)
        runs = read_csv(os.path.join(a, "runs.csv"))
        self.run_dir = {r["label"]: str(r.get("dir", r.get("run_dir", ""))) for r in runs}
        self._taps = {}

    def runs(self, protocol=None):
        rows = [r for r in self.summary if protocol is None or r["protocol"] == protocol]
        return sorted(rows, key=lambda r: r["control"])

    def taps(self, label):
        """taps.csv of a run, tap 0 (the prepared pile) included"""
        if label not in self._taps:
            d = self.run_dir.get(label, "")
            self._taps[label] = read_csv(os.path.join(d, "taps.csv")) if d else []
        return self._taps[label]

    def cut(self, label):
        """the taps the analysis dropped from the start of a run as its transient"""
        for r in self.summary:
            if r["label"] == label and isinstance(r.get("discard"), float):
                return int(r["discard"])
        return self.discard

    def used(self, label, key):
        """a taps.csv column after the run's discarded transient (the rows the analysis used)"""
        cut = self.cut(label)  # taps 1…cut (tap 0 is the prepared pile, never used)
        return column([r for r in self.taps(label) if r.get("tap", 0) > cut], key)

    def segregation(self, label):
        d = self.run_dir.get(label, "")
        return read_csv(os.path.join(d, "segregation.csv")) if d else []

    def beta_cov(self, names):
        """the bootstrap covariance (1/m⁴) of the named β̂ (joint:<label>,
        direct:<reference>:<label>) from beta_cov.csv; None where it is absent or incomplete"""
        rows = {r["quantity"]: r for r in self._cov}
        if not names or not self.replicas or any(n not in rows for n in names):
            return None
        c = np.array([[rows[a].get(b, float("nan")) for b in names] for a in names], float)
        return c if np.all(np.isfinite(c)) else None

    def primary_beta(self):
        ref = self.info.get("reference")
        return [r for r in self.beta if r.get("reference") == ref]


def phi_errors(study, row):
    """(error of φ̄, error of σ_φ, degrees of freedom) of a run: from batch means of its per-tap
    series where they are shipped, else the analysis' τ-corrected errors (dof None: normal)"""
    phi = study.used(row["label"], "phi") if study.taps(row["label"]) else []
    if len(phi) >= 10:
        _, em, dof = batch_err(phi)
        _, es, _ = batch_err([phi], lambda x: np.std(x, ddof=1))
        return em, es, dof
    return row["phi_err"], sigma_err(row), None


def sigma_err(row):
    """standard error of σ_φ from its τ-corrected 95 % chi-square interval"""
    return (row["sigma_hi_tau"] - row["sigma_lo_tau"]) / (2 * 1.96)


def quadron_phi(beta, a, phi_rlp=0.81, phi_rcp=0.855):
    """(P.26): 1/φ̄ = 1/φ_rlp + a/β − Δ·coth(βΔ/a), Δ = 1/φ_rlp − 1/φ_rcp, a = N z̄/V_g"""
    d = 1 / phi_rlp - 1 / phi_rcp
    u = beta * d / a
    coth = 1 / math.tanh(u) if abs(u) > 1e-8 else 1 / u + u / 3
    return 1 / (1 / phi_rlp + a / beta - d * coth)


def taps_needed(n, err, target):
    """taps per value for the standard error to fall from err (with n taps) to target"""
    if not (err > 0 and target > 0):
        return float("nan")
    return n * (err / target) ** 2


def steady_window(label, study, lo, hi):
    """φ over taps lo…hi against the steady taps after the transient: (difference of the means,
    its error, degrees of freedom). The window's taps are too few for their own error: it is the
    steady part's long-run variance (n·err² from batch means) over the window's length, an upper
    bound for positively correlated taps; the test is Student's t of the batches' dof."""
    rows = study.taps(label)
    phi = column([r for r in rows if lo <= r.get("tap", -1) <= hi], "phi")
    steady = study.used(label, "phi")
    m, em, dof = batch_err(steady)
    if not (len(phi) and em > 0):  # nan or a constant series: no test
        return float("nan"), float("nan"), 0
    return float(phi.mean()) - m, math.sqrt(len(steady) * em * em / len(phi) + em * em), dof


NEG, ROT = "negative_g", "rotating_g"
NEXT = {"smoke": "quick", "quick": "standard", "standard": "full", "full": "more taps than the paper's"}


def _save(study, fig, name):
    rel = os.path.join("charts", name + ".png")
    fig.tight_layout()
    fig.savefig(os.path.join(study.folder, rel), dpi=90)
    plt.close(fig)
    return rel


def _finish(st, fig, ax, xlabel, ylabel, name, fontsize=8, ncol=1):
    """label the axes, add the legend and save the chart; its path relative to the report"""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=fontsize, ncol=ncol)
    return _save(st, fig, name)


def _fig(w=6.4, h=3.8):
    return plt.subplots(figsize=(w, h))


def _pm(v, e, d=4):
    return f"{v:.{d}f} ± {1.96 * e:.{d}f}" if math.isfinite(e) else f"{v:.{d}f}"

"""Reading a Random Force Model reproduction (DIR/analysis/{reference,structure,ring}) and
the helpers its claims share: files, intervals, the steady-state gate, charts, a weighted fit."""
import csv
import json
import math
import os
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .batch import batch_err, normal_score  # noqa: E402
from .rfm_conditions import THESIS  # noqa: E402
from .verdicts import UNRESOLVED, Verdict, t_of  # noqa: E402

CUT = 1e-7        # 1D gaps below this (units of L′) are mostly touching disks: their overlap
N_THESIS = THESIS["xi2"]["N_from"]  # §3.1.3: "We have ignored data for … 100, 158 or 251 particles"
ORDER = ["smoke", "quick", "standard", "full"]


class Missing(Exception):
    """a file or a fit that the claim needs is not there"""


def _csv(path):
    """columns (numpy arrays) and metadata of an analysis CSV: the sidecar NAME.json, or the
    '# key=value' lines that older files have above the header"""
    if not os.path.exists(path):
        raise Missing(f"{path} is missing")
    with open(path) as f:
        lines = [x for x in f if x.strip()]
    meta = {k.strip(): float(v) for k, v in
            (x.lstrip("# ").split("=", 1) for x in lines if x.startswith("#") and "=" in x)}
    side = os.path.splitext(path)[0] + ".json"
    if os.path.exists(side):
        with open(side) as f:
            meta.update({k: math.nan if v is None else float(v) for k, v in json.load(f).items()})
    rows = list(csv.reader(x for x in lines if not x.startswith("#")))
    if len(rows) < 2:
        raise Missing(f"{path} has no rows")
    a = np.array([[float(c) if c.strip() else math.nan for c in r] for r in rows[1:]], float)
    return {h.strip(): a[:, i] for i, h in enumerate(rows[0])}, meta


SEED = re.compile(r"(?:^|_)seed=([^_]+)$")  # the seed is the sweep's last (fastest) parameter


def _runs(d, sweep):
    """the points of analysis/<sweep>/rfm_summary.json: the runs grouped by their label without
    its seed=K part, each point the fields of its first run (with its rfm.json as 'info') and
    'runs', every seed's run"""
    p = os.path.join(d, "analysis", sweep, "rfm_summary.json")
    if not os.path.exists(p):
        raise Missing(f"analysis/{sweep}/rfm_summary.json is missing (sweep not run or analysed)")
    with open(p) as f:
        runs = json.load(f)["runs"]
    if not runs:
        raise Missing(f"analysis/{sweep}: no run with steady samples")
    points = {}
    for r in runs:
        r["adir"] = os.path.join(d, "analysis", sweep, r["label"])
        q = os.path.join(r["adir"], "rfm.json")
        r["info"] = {}
        if os.path.exists(q):
            with open(q) as f:
                r["info"] = json.load(f)
        m = SEED.search(r["label"])
        r["seed"] = m.group(1) if m else None
        points.setdefault(SEED.sub("", r["label"]) if m else r["label"], []).append(r)
    out = []
    for base, rs in points.items():
        pt = dict(rs[0], label=base, runs=rs)
        pt["name"] = base.split("=")[-1] if len(points) > 1 and base else sweep
        for r in rs:
            r["name"] = pt["name"] + (f" seed {r['seed']}" if len(rs) > 1 else "")
        out.append(pt)
    return out


def t_blocks(adir):
    """T(t) of a run in blocks of fixed duration (temperature_blocks.csv of its analysis folder):
    columns t (each block's first sample), n, T, T_sd, steady (bool); 'end', the time of the last
    sample; 'tau', the steady samples' τ_int (samples); 'dt', the sample interval (s)"""
    c, meta = _csv(os.path.join(adir, "temperature_blocks.csv"))
    dt = meta.get("sample_interval", math.nan)
    return dict(c, steady=c["steady"] != 0, end=float(c["t"][-1] + (c["n"][-1] - 1) * dt),
                tau=meta.get("tau_int", math.nan), dt=dt, block=meta.get("block", math.nan))


def pooled(b, sel):
    """the samples of the blocks `sel` (a mask) pooled: their mean, its error with the steady
    samples' τ_int, sd·√(2τ/n) (verdicts.mean_err on those samples), their standard deviation
    and count; nan below two samples"""
    n, T, sd = b["n"][sel], b["T"][sel], b["T_sd"][sel]
    N = float(n.sum())
    if N < 2:
        return math.nan, math.nan, math.nan, N
    m = float((n * T).sum() / N)
    s = math.sqrt(float(((n - 1) * sd ** 2 + n * (T - m) ** 2).sum()) / (N - 1))
    return m, s * math.sqrt(2.0 * b["tau"] / N), s, N


def steady_series(adir):
    """a run's steady T(t): every steady sample (temperature.csv), else the means of its steady
    blocks of full length (temperature_blocks.csv; batches of whole blocks are batches of
    samples); None when the run has neither file"""
    p = os.path.join(adir, "temperature.csv")
    if os.path.exists(p):
        return _csv(p)[0]["T"]
    try:
        b = t_blocks(adir)
    except Missing:
        return None
    full = b["steady"] & (b["n"] >= b["n"][b["steady"]].max()) if b["steady"].any() else b["steady"]
    return b["T"][full]


def run_mean(adir, value=math.nan, err=math.nan):
    """a run's steady ⟨T⟩ with its batch-means error and degrees of freedom (batch.batch_err):
    τ_int from a series only tens of τ long comes out low, and a χ² on the error sd·√(2τ/n)
    rejects a steady T several times too often; (value, err, None) when no T(t) is there"""
    x = steady_series(adir)
    if x is None or len(x) < 10:
        return value, err, None
    m, e, dof = batch_err(x)
    return m, e, dof


def satterthwaite(coef, errors, dofs):
    """the degrees of freedom of Σ c_k x_k whose errors are estimated with dofs (None: exact)
    (Welch–Satterthwaite); None when every error is exact"""
    terms = [(c * e) ** 2 for c, e in zip(coef, errors)]
    if all(d is None for d in dofs):
        return None
    den = sum(t * t / d for t, d in zip(terms, dofs) if d is not None and d > 0)
    return sum(terms) ** 2 / den if den > 0 else None


def mean_of(T, E, dofs):
    """the plain mean of values T with errors E: mean, error, degrees of freedom. Equal weights:
    weights 1/E² from errors of a few degrees of freedom favour the runs whose error came out
    low by chance, and a test on their mean rejects several times its level"""
    T, E = np.asarray(T, float), np.asarray(E, float)
    c = np.full(len(T), 1.0 / len(T))
    return float(T.mean()), float(np.sqrt(((c * E) ** 2).sum())), satterthwaite(c, E, dofs)


def contrasts(T, E, dofs):
    """Helmert contrasts of values that the claim says are equal, each value less the mean of
    those before it over its error (equal weights, as in mean_of): n − 1 unit normals under the
    null, independent for equal errors; errors estimated with dofs give each contrast its
    Welch–Satterthwaite t, turned into the normal score of the same tail"""
    T, E, z = np.asarray(T, float), np.asarray(E, float), []
    for k in range(1, len(T)):
        coef = np.append(np.full(k, -1.0 / k), 1.0)
        t = float((coef * T[:k + 1]).sum()) / math.sqrt(float(((coef * E[:k + 1]) ** 2).sum()))
        nu = satterthwaite(coef, E[:k + 1], dofs[:k + 1])
        z.append(t if nu is None else normal_score(t, nu))
    return z


def seed_mean(values, errors, dofs=None):
    """a point's value from its seeds: their mean; its error the larger of the within-run error
    (the runs' errors combined) and the scatter between seeds (the standard error of their mean),
    which it was, and the degrees of freedom of a test on it (one seed: the run's own, dofs[0],
    None for normal)"""
    v, e = np.asarray(values, float), np.asarray(errors, float)
    if len(v) == 1:  # one seed: the run's own value, error and degrees of freedom, untouched
        return dict(value=float(v[0]), err=float(e[0]), within=float(e[0]), between=math.nan,
                    seeds=1, which="within the run", dof=None if dofs is None else dofs[0])
    within = float(np.sqrt((e ** 2).sum()) / len(v))
    between = float(v.std(ddof=1) / math.sqrt(len(v)))
    big = not (within >= between)  # a NaN within-run error gives way to the seeds' scatter
    # Student's t of n − 1 dof whichever is larger: the t test on the seeds' scatter alone has
    # its nominal size, and a larger error only lowers it (a within-run error that wins by
    # chance may still miss a scatter the runs do not see)
    return dict(value=float(v.mean()), err=between if big else within, within=within,
                between=between, seeds=len(v), which="between seeds" if big else "within runs",
                dof=len(v) - 1)


def seed_text(s, unit=""):
    """'' for one seed, else both errors of a seed mean and which one the verdict uses"""
    if s["seeds"] < 2:
        return ""
    t = t_of(0.05, s["seeds"] - 1)
    return (f" (mean of {s['seeds']} seeds; 95 % scatter between seeds ± {t * s['between']:.2g}"
            f"{unit}, within runs ± {1.96 * s['within']:.2g}{unit}: the verdict uses the larger, "
            f"{s['which']}, with Student's t of {s['dof']} degrees of freedom)")


def _ci(v, e, dof=None):
    """value ± its 95 % interval (normal, or Student's t of dof degrees of freedom when the error
    comes from dof + 1 seeds), rounded to the interval's second digit"""
    if v is None or not math.isfinite(v):
        return "n/a"
    if e is None or not (math.isfinite(e) and e > 0):
        return f"{v:.3g}"
    half = e * (t_of(0.05, dof) if dof else 1.96)
    n = max(0, 1 - math.floor(math.log10(half)))
    return f"{v:.{n}f} ± {half:.{n}f}"


def _gate(v, runs, need=THESIS["T-start"]["discard_s"]):
    """steady-state claims need the thesis' first second discarded (§2.2.3, §2.3.2); runs whose
    plan states its conditions are held to each claim's own (rfm_conditions) first"""
    t = min(q["info"].get("t_steady", q["info"].get("discard_time", 0.0))
            for r in runs for q in r.get("runs", [r]))
    if v.verdict != UNRESOLVED and t < need - 1e-6:
        return Verdict(UNRESOLVED, f"the runs discard only {t:.2g} s of transient, the thesis measures "
                       f"after the first second; at face value: {v.verdict}, {v.reason}",
                       v.null, v.alternative, v.power, v.scale)
    return v


def _chart(d, cid, draw, wide=False):
    rel = os.path.join("charts", f"rfm_{cid}.png")
    fig = plt.figure(figsize=(11, 4.4) if wide else (6.8, 4.4))
    try:
        draw(fig) if wide else draw(fig.gca())
        fig.tight_layout()
        fig.savefig(os.path.join(d, rel), dpi=100)
        return rel
    except Exception as e:  # a chart never costs the claim
        print(f"rfm.py: chart {cid} skipped: {type(e).__name__}: {e}")
        return ""
    finally:
        plt.close(fig)


def _ax(ax, title, xl, yl, xlog=False, ylog=False, fs=8):
    ax.set(xlabel=xl, ylabel=yl, xscale="log" if xlog else "linear", yscale="log" if ylog else "linear")
    ax.set_title(title, fontsize=10)
    ax.legend(fontsize=fs)


def _wfit(x, y, s):
    """weighted line y = a + b x: b, σ_b (inflated by √χ²_r when > 1), a"""
    (b, a), cov = np.polyfit(x, y, 1, w=1 / s, cov="unscaled")
    chi2, dof = float((((y - a - b * x) / s) ** 2).sum()), len(x) - 2
    return b, math.sqrt(cov[0, 0] * (chi2 / dof if dof > 0 and chi2 > dof else 1.0)), a

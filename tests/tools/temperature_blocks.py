"""temperature_blocks.csv as `gransim analyze` writes it (src/analysis/rfm_blocks.cpp), made from
a synthetic T(t) for the report's tests (ar1: a correlated one): blocks [kΔ, (k+1)Δ) split at the steady start, each
with its count, mean and spread, and the steady samples' τ_int in the sidecar."""
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python"))
from gransim.reproduce.verdicts import tau_int  # noqa: E402


def write(adir, t, T, steady=None, block=0.05, dt=None):
    t, T = np.asarray(t, float), np.asarray(T, float)
    steady = np.ones(len(t), bool) if steady is None else np.asarray(steady, bool)
    k = np.floor(t / block + 1e-9)
    new = np.ones(len(t), bool)
    new[1:] = (k[1:] != k[:-1]) | (steady[1:] != steady[:-1])
    starts = np.nonzero(new)[0]
    n = np.diff(np.append(starts, len(t)))
    s = np.add.reduceat(T, starts)
    m = s / n
    ss = np.add.reduceat((T - np.repeat(m, n)) ** 2, starts)
    sd = np.where(n > 1, np.sqrt(ss / np.maximum(n - 1, 1)), 0.0)
    with open(os.path.join(adir, "temperature_blocks.csv"), "w") as f:
        f.write("t,n,T,T_sd,steady\n" + "".join(
            f"{a!r},{c},{x!r},{y!r},{int(z)}\n"
            for a, c, x, y, z in zip(t[starts], n, m, sd, steady[starts])))
    x, ts = T[steady], t[steady]
    tau, mid = tau_int(x), 0.5 * (ts[0] + ts[-1])
    meta = dict(block=block, sample_interval=dt if dt else float(np.median(np.diff(t))),
                samples=len(x), tau_int=tau, T_mean=float(x.mean()),
                T_err=float(x.std(ddof=1) * math.sqrt(2 * tau / len(x))),
                tau_int_first=tau_int(x[ts < mid]), tau_int_second=tau_int(x[ts >= mid]))
    with open(os.path.join(adir, "temperature_blocks.json"), "w") as f:
        json.dump(meta, f)


def ar1(rng, n, a, sigma):
    """x_i = a x_{i−1} + N(0, σ²(1 − a²)): standard deviation σ, τ_int = (1 + a)/(2(1 − a));
    x_{s+i} = a^i (a x_{s−1} + Σ_{j≤i} a^{−j} e_{s+j}) over chunks short enough for a^{−j}"""
    e = rng.normal(0, sigma * math.sqrt(1 - a * a), n)
    x = np.empty(n)
    v, p = rng.normal(0, sigma), a ** np.arange(200.0)
    for s in range(0, n, 200):
        c = e[s:s + 200]
        x[s:s + len(c)] = p[:len(c)] * (a * v + np.cumsum(c / p[:len(c)]))
        v = x[s + len(c) - 1]
    return x

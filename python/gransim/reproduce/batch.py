"""Errors of short serially correlated series (tens to thousands of taps) with their degrees of
freedom, so that a test on them keeps its stated level.

The integrated autocorrelation time estimated from a few dozen taps comes out low, and a
normal test on the error it gives rejects a true null far more often than its level (at 35
taps and τ = 1.5, twenty times at the 0.14 % level). Batch means do not need τ: the series is
cut into b = ⌊√n⌋ contiguous batches (at least 5, at most 30; the first n mod b taps dropped
from the batches, not from the estimate), the scatter of a statistic over the batches (the
delete-one-batch jackknife; for a mean, the batch means' standard error) gives its error, and
the test is Student's t of b − 1 degrees of freedom. Batches of m taps still share their
edges: the batch variance is low by ≈ 2τ/m (the first-order bias for a positively correlated
series), so it is divided by 1 − 2τ̂/m (at most by 2). With that, the two-sided rejection rate
of a true mean at 5 % and 0.14 % stays within 1.3 times its level for 35–250 taps and τ ≤ 1.5
(AR(1) series, 10⁴ draws each; tests/tools/test_twins.py repeats it)."""
import math

import numpy as np

from .verdicts import _N, t_sf2, tau_int

MIN_BATCHES, MAX_BATCHES = 5, 30


def batches(n):
    """the number of batches and taps per batch for a series of n taps (b = 0: too short)"""
    b = min(max(int(math.isqrt(n)), MIN_BATCHES), MAX_BATCHES) if n >= 2 * MIN_BATCHES else 0
    return b, (n // b if b else 0)


def batch_err(cols, stat=None):
    """(value, standard error, degrees of freedom) of stat(*cols) over the whole series (stat
    None: the mean of the one column), the error from b contiguous batches (module docstring);
    nan error and 0 degrees of freedom for fewer than 10 taps"""
    cols = [np.asarray(c, float) for c in (cols if isinstance(cols, (list, tuple)) else [cols])]
    n = len(cols[0])
    if stat is None:
        stat = np.mean
    value = float(stat(*cols)) if n else float("nan")
    b, m = batches(n)
    if not b:
        return value, float("nan"), 0
    lo = n - b * m
    if stat is np.mean:
        y = cols[0][lo:].reshape(b, m).mean(axis=1)
        var = float(np.var(y, ddof=1)) / b
    else:
        keep = np.ones(b * m, bool)
        pseudo = []
        for i in range(b):
            keep[:] = True
            keep[i * m:(i + 1) * m] = False
            pseudo.append(stat(*(c[lo:][keep] for c in cols)))
        pseudo = np.asarray(pseudo, float)
        var = float((b - 1) / b * np.sum((pseudo - pseudo.mean()) ** 2))
    var /= max(1.0 - 2.0 * tau_int(cols[0]) / m, 0.5)
    return value, math.sqrt(var), b - 1


def normal_score(t, dof):
    """the standard normal deviate with the same two-sided tail probability as Student's t of
    dof degrees of freedom, signed as t (so a χ² of such scores keeps its level)"""
    if not math.isfinite(t):
        return t
    p = t_sf2(abs(t), dof)
    if p <= 0:
        return math.copysign(40.0, t)
    return math.copysign(_N.inv_cdf(1.0 - 0.5 * p), t)

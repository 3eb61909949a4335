"""Errors of short serially correlated series (tens to thousands of taps) with their degrees of
freedom, so that a test on them keeps its stated level.

The integrated autocorrelation time estimated from a few dozen taps comes out low, and a
normal test on the error it gives rejects a true null far more often than its level (at 35
taps and τ = 1.5, twenty times at the 0.14 % level). Batch means need τ only roughly: the series
is cut into b contiguous batches, b = ⌊√n⌋ (at least 5, at most 30) but fewer where a batch
would be shorter than 4τ̂ (at least 3; the first n mod b taps dropped from the batches, not from
the estimate), the scatter of a statistic over the batches (the delete-one-batch jackknife; for
a mean, the batch means' standard error) gives its error, and the test is Student's t of b − 1
degrees of freedom. Batches of m taps still share their edges: the batch variance is low by
≈ 2τ/m (the first-order bias for a positively correlated series), so it is divided by
1 − 2τ̂/m (at most by 2). With that, the two-sided rejection rate of a true mean at 5 % and
0.14 % stays within 1.4 times its level for 35–2500 taps and τ ≤ 1.5 (AR(1) series, 6000 draws
each; tests/tools/test_twins_short.py repeats it at the claims' level), within 2.1 times at τ = 3
and n ≥ 35, and within 4 times for series only 12 τ long (500 samples at τ = 40), where τ_int
errors reject 20 times too often."""
import math

import numpy as np

from .verdicts import _N, P_KEEP, f_sf, t_sf2, tau_int

MIN_BATCHES, MAX_BATCHES = 5, 30


def batches(n, tau=0.5):
    """the number of batches and taps per batch for a series of n taps whose integrated
    autocorrelation time is about tau (b = 0: too short)"""
    if n < 2 * MIN_BATCHES:
        return 0, 0
    b = min(max(math.isqrt(n), MIN_BATCHES), MAX_BATCHES)
    b = max(min(b, int(n / (4.0 * tau))), 3)
    return b, n // b


def batch_err(cols, stat=None):
    """(value, standard error, degrees of freedom) of stat(*cols) over the whole series (stat
    None: the mean of the one column), the error from b contiguous batches (module docstring);
    nan error and 0 degrees of freedom for fewer than 10 taps"""
    cols = [np.asarray(c, float) for c in (cols if isinstance(cols, (list, tuple)) else [cols])]
    n = len(cols[0])
    if stat is None:
        stat = np.mean
    value = float(stat(*cols)) if n else float("nan")
    if n < 2 * MIN_BATCHES:
        return value, float("nan"), 0
    tau = tau_int(cols[0])
    b, m = batches(n, tau)
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
    var /= max(1.0 - 2.0 * tau / m, 0.5)
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


def f_isf(p, d1, d2):
    """the value of Fisher's F of (d1, d2) degrees of freedom exceeded with probability p"""
    lo, hi = 0.0, 1.0
    while f_sf(hi, d1, d2) > p:
        hi *= 2.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f_sf(mid, d1, d2) > p else (lo, mid)
    return hi


def f_power(lam, d1, d2, alpha=P_KEEP):
    """P(an F test of (d1, d2) degrees of freedom at level alpha rejects) when the numerator's
    χ² has noncentrality λ: Patnaik's approximation of the noncentral χ² by a scaled central one,
    c·χ²_ν with c = (d1 + 2λ)/(d1 + λ), ν = (d1 + λ)²/(d1 + 2λ)"""
    if not (math.isfinite(lam) and lam >= 0 and d1 >= 1 and d2 >= 1):
        return float("nan")
    c, nu = (d1 + 2 * lam) / (d1 + lam), (d1 + lam) ** 2 / (d1 + 2 * lam)
    return f_sf(f_isf(alpha, d1, d2) * d1 / (c * nu), nu, d2)

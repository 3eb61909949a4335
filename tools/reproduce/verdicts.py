"""Verdicts on a source's claims from measured values with errors.

Every function returns a Verdict: *agrees*, *disagrees* or *not resolved*, and one sentence
with the numbers that decided it. Errors are standard errors (1σ); a claim agrees when the
measurement is within 2σ of what the source says, disagrees when it is more than 3σ away (or
the feature the source describes is excluded at 95 %), and is not resolved in between or when
the errors are too large to tell.
"""
from dataclasses import dataclass
import math

import numpy as np

AGREES = "agrees"
DISAGREES = "disagrees"
UNRESOLVED = "not resolved"


@dataclass
class Verdict:
    verdict: str
    reason: str

    def __iter__(self):
        return iter((self.verdict, self.reason))


def _finite(*v):
    return all(x is not None and math.isfinite(x) for x in v)


def compare_value(measured, err, source, source_err=0.0, tolerance=0.0, resolve=None,
                  fmt="{:.4g}"):
    """A number against the source's number.

    tolerance: an allowed difference on top of the errors (for "≈" in the source);
    resolve: the largest error that can decide at all (None: any finite error).
    """
    if not _finite(measured, err):
        return Verdict(UNRESOLVED, "no finite measurement")
    s = math.hypot(err, source_err)
    d = abs(measured - source)
    text = (f"measured {fmt.format(measured)} ± {fmt.format(err)}, source {fmt.format(source)}"
            + (f" ± {fmt.format(source_err)}" if source_err else "")
            + (f" (± {fmt.format(tolerance)} allowed)" if tolerance else ""))
    if resolve is not None and err > resolve:
        return Verdict(UNRESOLVED, text + f"; the error exceeds {fmt.format(resolve)}")
    if d <= 2.0 * s + tolerance:
        return Verdict(AGREES, text)
    if d > 3.0 * s + tolerance:
        return Verdict(DISAGREES, text + f"; {(d - tolerance) / s:.1f}σ away")
    return Verdict(UNRESOLVED, text + f"; {(d - tolerance) / s:.1f}σ away")


def below_bound(measured, err, bound, fmt="{:.3g}"):
    """A non-negative quantity the source says stays below `bound` (e.g. |Δφ|/φ < 1e-4)."""
    if not _finite(measured, err):
        return Verdict(UNRESOLVED, "no finite measurement")
    hi, lo = measured + 2.0 * err, measured - 2.0 * err
    text = f"measured {fmt.format(measured)} ± {fmt.format(err)}, bound {fmt.format(bound)}"
    if hi < bound:
        return Verdict(AGREES, text)
    if lo > bound:
        return Verdict(DISAGREES, text + " (excluded at 95 %)")
    return Verdict(UNRESOLVED, text + "; the 95 % interval straddles the bound")


def _depths(y, kind):
    """depth of the extremum at each interior point: how far the curve rises (min) or falls
    (max) on both sides of it before the ends"""
    s = 1.0 if kind == "min" else -1.0
    z = s * np.asarray(y, float)
    out = np.full(len(z), -np.inf)
    for i in range(1, len(z) - 1):
        out[i] = min(z[:i].max(), z[i + 1:].max()) - z[i]
    return out


def extremum(x, y, err, kind="min", expect_at=None, min_effect=0.0, fmt="{:.4g}"):
    """Does y(x) have an interior minimum (or maximum) near `expect_at`?

    The deepest interior point i is the candidate. It exists when y rises (falls) by more than
    2σ on both sides of it: some point to its left and some point to its right each differ from
    it by over 2σ. It is then compared with expect_at: agrees when expect_at lies between the
    candidate's neighbours. Without it, the claim is excluded when even the 95 % upper bound of
    the deepest interior feature (depth + 2σ√2, σ the largest error) stays below min_effect,
    the smallest feature that would count as the one the source describes.
    """
    x, y, err = (np.asarray(v, float) for v in (x, y, err))
    order = np.argsort(x)
    x, y, err = x[order], y[order], err[order]
    word = "minimum" if kind == "min" else "maximum"
    if len(x) < 3 or not np.all(np.isfinite(y)) or not np.all(np.isfinite(err)):
        return Verdict(UNRESOLVED, f"fewer than 3 points with finite values: no interior {word}"), None
    d = _depths(y, kind)
    i = int(np.argmax(d))
    s = 1.0 if kind == "min" else -1.0
    left = (s * (y[:i] - y[i])) / np.hypot(err[:i], err[i])
    right = (s * (y[i + 1:] - y[i])) / np.hypot(err[i + 1:], err[i])
    zl, zr = float(left.max()), float(right.max())
    where = f"x = {fmt.format(x[i])}"
    if zl > 2.0 and zr > 2.0:
        text = (f"{word} at {where}, the curve {'rises' if kind == 'min' else 'falls'} by "
                f"{zl:.1f}σ to its left and {zr:.1f}σ to its right")
        if expect_at is None:
            return Verdict(AGREES, text), float(x[i])
        lo = x[i - 1]
        hi = x[i + 1]
        if lo <= expect_at <= hi:
            return Verdict(AGREES, text + f"; the source's {fmt.format(expect_at)} lies between "
                           f"its neighbours {fmt.format(lo)} and {fmt.format(hi)}"), float(x[i])
        return Verdict(DISAGREES, text + f"; the source puts it at {fmt.format(expect_at)}, "
                       f"outside [{fmt.format(lo)}, {fmt.format(hi)}]"), float(x[i])
    upper = max(float(d[i]), 0.0) + 2.0 * math.sqrt(2.0) * float(err.max())
    if min_effect > 0.0 and upper < min_effect:
        return Verdict(DISAGREES, f"no interior {word}: the deepest feature ({where}) is at most "
                       f"{fmt.format(upper)} at 95 %, below the {fmt.format(min_effect)} "
                       f"that the claim needs"), None
    return Verdict(UNRESOLVED, f"no {word} resolved: the deepest interior point ({where}) "
                   f"differs by {zl:.1f}σ / {zr:.1f}σ from the sides"), None


def step_change(x, y, err, expected_step, factor=2.0, fmt="{:.4g}"):
    """A crossover: y changes from its value at the smallest x to its value at the largest
    by about `expected_step` (sign included). Agrees when the change has the source's sign
    at 95 % and its 95 % interval meets [step/factor, step·factor]; disagrees when the 95 %
    interval excludes that range."""
    x, y, err = (np.asarray(v, float) for v in (x, y, err))
    order = np.argsort(x)
    y, err = y[order], err[order]
    if len(y) < 2:
        return Verdict(UNRESOLVED, "fewer than 2 points")
    step = float(y[-1] - y[0])
    e = float(math.hypot(err[-1], err[0]))
    lo, hi = step - 2 * e, step + 2 * e
    want = sorted((expected_step / factor, expected_step * factor))
    text = (f"change {fmt.format(step)} ± {fmt.format(e)} from the lowest to the highest value, "
            f"source ≈ {fmt.format(expected_step)}")
    same_sign = lo > 0 if expected_step > 0 else hi < 0
    meets = hi >= want[0] and lo <= want[1]
    if same_sign and meets:
        return Verdict(AGREES, text)
    if not meets:
        return Verdict(DISAGREES, text + f"; the 95 % interval [{fmt.format(lo)}, "
                       f"{fmt.format(hi)}] excludes [{fmt.format(want[0])}, {fmt.format(want[1])}]")
    return Verdict(UNRESOLVED, text + "; the sign is not resolved at 95 %")


def chi2_consistent(residuals, errors, label="residuals", p_agree=0.05, p_disagree=0.01):
    """Values that the source says are zero (or one curve): χ² of residual/error.
    Agrees for p > p_agree, disagrees for p < p_disagree."""
    r = np.asarray(residuals, float)
    e = np.asarray(errors, float)
    ok = np.isfinite(r) & np.isfinite(e) & (e > 0)
    r, e = r[ok], e[ok]
    if len(r) < 2:
        return Verdict(UNRESOLVED, f"fewer than 2 {label} with errors"), float("nan")
    chi2 = float(np.sum((r / e) ** 2))
    dof = len(r)
    p = chi2_sf(chi2, dof)
    text = f"χ² = {chi2:.1f} for {dof} {label} (p = {p:.3g})"
    if p > p_agree:
        return Verdict(AGREES, text), p
    if p < p_disagree:
        return Verdict(DISAGREES, text), p
    return Verdict(UNRESOLVED, text), p


def chi2_sf(chi2, dof):
    """P(χ²_dof > chi2): the regularized upper incomplete gamma function Q(dof/2, chi2/2)."""
    a, x = 0.5 * dof, 0.5 * chi2
    if x <= 0:
        return 1.0
    if x < a + 1.0:  # series for P, then Q = 1 − P
        term = total = 1.0 / a
        n = a
        for _ in range(1000):
            n += 1.0
            term *= x / n
            total += term
            if abs(term) < abs(total) * 1e-15:
                break
        return max(0.0, 1.0 - total * math.exp(-x + a * math.log(x) - math.lgamma(a)))
    # continued fraction for Q (Lentz)
    b = x + 1.0 - a
    c = 1.0 / 1e-300
    d = 1.0 / b
    h = d
    for i in range(1, 1000):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = 1e-300 if abs(d) < 1e-300 else d
        c = b + an / c
        c = 1e-300 if abs(c) < 1e-300 else c
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < 1e-15:
            break
    return math.exp(-x + a * math.log(x) - math.lgamma(a)) * h


def tau_int(x, c=5.0):
    """Integrated autocorrelation time (Sokal's window), in samples; 0.5 for white noise."""
    x = np.asarray(x, float)
    n = len(x)
    if n < 4 or np.var(x) == 0:
        return 0.5
    d = x - x.mean()
    f = np.fft.rfft(d, 2 * n)
    acf = np.fft.irfft(f * np.conj(f))[:n]
    rho = acf / acf[0]
    tau = 0.5
    for m in range(1, n // 2):
        tau += rho[m]
        if m >= c * tau:
            return max(tau, 0.5)
    return max(tau, 0.5)


def mean_err(x):
    """mean and its standard error with serially correlated samples (n_eff = n/2τ)"""
    x = np.asarray(x, float)
    if len(x) < 2:
        return float("nan"), float("nan")
    t = tau_int(x)
    return float(x.mean()), float(x.std(ddof=1) * math.sqrt(2.0 * t / len(x)))

"""Verdicts on a source's claims from measured values with errors.

Every function returns a Verdict: *agrees*, *disagrees* or *not resolved*, one sentence with
the numbers that decided it, and the test behind it: its null hypothesis, the alternative that
the source itself names or shows, and the power of the test against that alternative at the
run's length. Errors are standard errors (1σ).

One rule for every claim:
- a claim that a quantity equals the source's (or zero, or lies below a bound) *agrees* when
  the test keeps it at the 5 % level and would have rejected the source's alternative with at
  least 80 % power; it *disagrees* when the test rejects it at the 1 % level;
- a claim that a feature exists (a minimum, offsets between protocols) *agrees* when
  the test finds it at the 5 % level with at least 80 % power against a feature of the
  source's size; it *disagrees* when the test misses it although it would have found a
  feature of the source's size with at least 99 % power;
- anything else is *not resolved*, with the length factor (more taps, seconds) that would give
  the test 80 % power.
A tolerance enters only where the source states a precision; the caller quotes it.

Correlated estimates (the β̂ of different runs share references and neighbours): where the
analysis ships their bootstrap covariance (analysis/beta_cov.csv) the tests are generalised
least squares, χ² = rᵀC⁻¹r, with C guarded by cov_inverse: the eigenvalues of its correlation
matrix are floored at n/R (n estimates, R bootstrap replicas: the scale of the noise in the
spectrum of a covariance estimated from R draws, below which a direction is not resolved), and
C⁻¹ is scaled by (R − n − 2)/(R − 1), the mean bias of the inverse of a covariance estimated
from R draws (Wishart); with R ≤ n + 2 there is no usable covariance. Where no covariance is
shipped the errors are taken as independent and the claim says so; it may then disagree but
not agree (without_covariance), because positive correlations between the estimates make an
independent χ² of their differences lenient.
"""
from dataclasses import dataclass
import functools
import math
from statistics import NormalDist

import numpy as np

AGREES = "agrees"
DISAGREES = "disagrees"
UNRESOLVED = "not resolved"

P_KEEP = 0.05      # a null kept at this level can agree
P_REJECT = 0.01    # a null rejected at this level disagrees
POWER = 0.80       # an agreement needs this power against the source's alternative
POWER_MISS = 0.99  # a feature missed by a test of this power disagrees

_N = NormalDist()


@dataclass
class Verdict:
    verdict: str
    reason: str
    null: str = ""           # what the test assumes
    alternative: str = ""    # the source's alternative, with its size
    power: float = float("nan")  # P(the test detects the alternative) at the run's length
    scale_: float = float("nan")  # length factor for 80 % power (1 = enough now)
    power_at: object = None  # k ↦ the power at k times the run's length (errors ∝ 1/√k)

    @property
    def scale(self):
        """the length factor for 80 % power, found from power_at when first asked"""
        if not math.isfinite(self.scale_) and self.power_at is not None:
            self.scale_ = scale_for(self.power_at)
        return self.scale_

    def __iter__(self):
        return iter((self.verdict, self.reason))

    def need(self, n, unit="taps"):
        """the length that would give the test 80 % power, in `unit`, from the present n"""
        if math.isfinite(self.power) and not math.isfinite(self.scale) and self.power < POWER:
            return ("no run length reaches 80 % power: the source's own uncertainty (or the "
                    "alternative's size) limits the test")
        if not (math.isfinite(self.scale) and n and n > 0):
            return ""
        if self.scale <= 1.0:
            return (f"the power suffices ({self.power:.2f}); p lies between 1 % and 5 %: longer "
                    f"runs than {n:.3g} {unit} decide")
        return f"≈ {self.scale * n:.3g} {unit} for 80 % power (now {n:.3g}, power {self.power:.2f})"


def _finite(*v):
    return all(x is not None and math.isfinite(x) for x in v)


def phi(x):
    return _N.cdf(x)


def z_of(p):
    """the standard normal quantile z with P(Z > z) = p"""
    return _N.inv_cdf(1.0 - p)


def t_of(p, dof):
    """Student's t quantile with P(|T_dof| > t) = p (bisection on t_sf2)"""
    lo, hi = 0.0, 1e4
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if t_sf2(mid, dof) > p else (lo, mid)
    return hi


def power_two_sided(effect, sigma, tolerance=0.0, alpha=P_KEEP, dof=None):
    """P(|d̂| − tolerance > c·σ) when d̂ ~ N(effect, σ), c = z_{α/2} (or Student's t quantile
    of dof degrees of freedom when σ is estimated from dof + 1 values)"""
    if not (_finite(effect, sigma) and sigma > 0):
        return float("nan")
    c = tolerance + (z_of(alpha / 2) if dof is None else t_of(alpha, dof)) * sigma
    return phi((abs(effect) - c) / sigma) + phi((-abs(effect) - c) / sigma)


def power_one_sided(effect, sigma, alpha=P_KEEP):
    """P(d̂ > z_α·σ) when d̂ ~ N(effect, σ), effect ≥ 0"""
    if not (_finite(effect, sigma) and sigma > 0):
        return float("nan")
    return phi(effect / sigma - z_of(alpha))


def scale_for(power_at, target=POWER):
    """the factor k by which a series must grow (errors ∝ 1/√k) for power_at(k) ≥ target;
    nan when even 10⁶ times the length does not reach it"""
    p1 = power_at(1.0)
    if not math.isfinite(p1):
        return float("nan")
    if p1 >= target:
        lo, hi = 1e-6, 1.0
        if power_at(lo) >= target:
            return lo
    else:
        lo, hi = 1.0, 1e6
        if power_at(hi) < target:
            return float("nan")
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        if power_at(mid) >= target:
            hi = mid
        else:
            lo = mid
    return hi


def decide(p, power, what_null, what_alt, text, scale, feature=False, fmt_p="{:.3g}",
           power_at=None, family=1):
    """the one rule (module docstring) from a p-value and a power; family: the number of tests
    whose any rejection makes the claim disagree (Bonferroni: each rejects at 1 %/family)"""
    pw = "no power (no alternative)" if not math.isfinite(power) else f"power {power:.2f}"
    if feature:  # the claim is the alternative: p tests "no feature"
        if p < P_KEEP and math.isfinite(power) and power >= POWER:
            v = AGREES
        elif p >= P_KEEP and math.isfinite(power) and power >= POWER_MISS:
            v = DISAGREES
        else:
            v = UNRESOLVED
    else:
        if p < P_REJECT / family:
            v = DISAGREES
        elif p > P_KEEP and math.isfinite(power) and power >= POWER:
            v = AGREES
        else:
            v = UNRESOLVED
    text = f"{text}; p = {fmt_p.format(p)}, {pw} against {what_alt}"
    return Verdict(v, text, what_null, what_alt, power, scale, power_at)


def compare_value(measured, err, source, source_err=0.0, tolerance=0.0, alternative=None,
                  precision="", fmt="{:.4g}", dof=None, family=1):
    """A number against the source's number.

    tolerance: the precision the source states (its ±, or the rounding of a printed value),
    quoted in `precision`; alternative: the smallest difference from the source that the
    source would call a failure (None: the source names none, so the test has no power and
    cannot agree); dof: err is a scatter estimated with dof degrees of freedom (the standard
    error of a mean over dof + 1 seeds, or of batch means), so the test is Student's t, not
    normal; family: decide's.
    """
    if not _finite(measured, err):
        return Verdict(UNRESOLVED, "no finite measurement", "", "", float("nan"))
    s = math.hypot(err, source_err)
    d = abs(measured - source)
    excess = max(d - tolerance, 0.0)
    if dof is not None and s > 0:
        p = t_sf2(excess / s, dof) if excess > 0 else 1.0
    else:
        p = 2.0 * (1.0 - phi(excess / s)) if s > 0 else (1.0 if excess == 0 else 0.0)
    text = (f"measured {fmt.format(measured)} ± {fmt.format(err)}, source {fmt.format(source)}"
            + (f" ± {fmt.format(source_err)}" if source_err else "")
            + (f" (± {fmt.format(tolerance)}: {precision})" if tolerance else "" if source_err else
               " (the source states no precision: the measurement's error alone)")
            + (f"; {excess / s:.1f}σ beyond it" if excess > 0 and s > 0 else "")
            + (f" (Student's t, {dof:.3g} degrees of freedom)" if dof is not None else "")
            + (f"; Bonferroni over {family} values: disagrees at p < {P_REJECT / family:.2g}"
               if family > 1 else ""))
    null = f"true value = {fmt.format(source)}" + (f" ± {fmt.format(tolerance)}" if tolerance else "")
    if alternative is None:
        return decide(p, float("nan"), null, "none named by the source", text, float("nan"),
                      family=family)
    def at(k):
        return power_two_sided(alternative, math.hypot(err / math.sqrt(k), source_err), tolerance,
                               dof=dof)
    alt = f"a difference of {fmt.format(alternative)}"
    return decide(p, at(1.0), null, alt, text, float("nan"), power_at=at, family=family)


def below_bound(measured, err, bound, ideal=0.0, fmt="{:.3g}", dof=None, family=1, folded=False):
    """A quantity the source says stays below `bound` (e.g. |Δφ|/φ < 1e-4). Null: the value
    is `ideal` (the claim holds with margin); alternative: the value is at the bound. Agrees when
    the one-sided 95 % upper limit is below the bound and the test of ideal against bound has
    ≥ 80 % power; disagrees when the one-sided 99 % lower limit is above the bound.
    dof: err estimated with dof degrees of freedom (Student's t, not normal); family: the number
    of runs whose any disagreement makes the claim disagree (Bonferroni, so the claim's level stays
    1 %); folded: the statistic is a modulus |x|, which exceeds a bound from both signs of x, so
    the lower limit is two-sided."""
    if not _finite(measured, err) or err <= 0:
        return Verdict(UNRESOLVED, "no finite measurement", "", "", float("nan"))
    a_rej = P_REJECT / family / (2 if folded else 1)

    def quantile(a):  # one-sided
        return z_of(a) if dof is None else t_of(2.0 * a, dof)
    q_keep = quantile(P_KEEP)
    upper = measured + q_keep * err
    lower = measured - quantile(a_rej) * err
    gap = bound - ideal

    def at(k):
        return phi(gap / (err / math.sqrt(k)) - q_keep)
    pw, k = at(1.0), float("nan")
    how = [f"Student's t, {dof} degrees of freedom"] if dof is not None else []
    if family > 1:
        how.append(f"Bonferroni over {family} runs")
    if folded:
        how.append("two-sided: the statistic is a modulus")
    lim = f"{100 * (1 - a_rej):.4g} %" + (f" ({'; '.join(how)})" if how else "")
    text = (f"measured {fmt.format(measured)} ± {fmt.format(err)}, bound {fmt.format(bound)}; "
            f"one-sided 95 % upper limit {fmt.format(upper)}")
    null = f"value = {fmt.format(ideal)}"
    alt = f"a value at the bound {fmt.format(bound)}"
    pw_text = f"power {pw:.2f} against {alt}"
    if lower > bound:
        return Verdict(DISAGREES, text + f"; the one-sided {lim} lower limit {fmt.format(lower)} "
                       f"exceeds the bound; {pw_text}", null, alt, pw, k, at)
    if upper < bound and pw >= POWER:
        return Verdict(AGREES, text + f" below the bound; {pw_text}", null, alt, pw, k, at)
    why = "above the bound" if upper >= bound else "below the bound, but"
    return Verdict(UNRESOLVED, f"{text} {why}; {pw_text}" + (f" ({'; '.join(how)})" if how else ""),
                   null, alt, pw, k, at)


def _depths(y, kind):
    """depth of the extremum at each interior point: how far the curve rises (min) or falls
    (max) on both sides of it before the ends"""
    s = 1.0 if kind == "min" else -1.0
    z = s * np.asarray(y, float)
    out = np.full(len(z), -np.inf)
    for i in range(1, len(z) - 1):
        out[i] = min(z[:i].max(), z[i + 1:].max()) - z[i]
    return out


def extremum_power(effect, sigma, z=2.0):
    """P(a dip of depth `effect` is seen by over z·σ√2 on both sides), σ each point's error"""
    if not (_finite(effect, sigma) and sigma > 0 and effect > 0):
        return float("nan")
    return phi(effect / (math.sqrt(2.0) * sigma) - z) ** 2


def extremum(x, y, err, kind="min", expect_at=None, effect=None, effect_source="", fmt="{:.4g}"):
    """Does y(x) have an interior minimum (or maximum) near `expect_at`?

    The deepest interior point i is the candidate. It is found when y rises (falls) by more
    than 2σ on both sides of it (each side a one-sided 2.3 % test, both together below 5 % for
    a flat curve); then it agrees when expect_at lies between the candidate's neighbours and
    the test had ≥ 80 % power against a feature of depth `effect` (the source's size, quoted
    in effect_source), and disagrees when expect_at lies outside and the curve there is off
    the extremum's value at the 1 % level. When no feature is found, it
    disagrees only if a feature of depth `effect` would have been found with ≥ 99 % power.
    """
    x, y, err = (np.asarray(v, float) for v in (x, y, err))
    order = np.argsort(x)
    x, y, err = x[order], y[order], err[order]
    word = "minimum" if kind == "min" else "maximum"
    null = f"no interior {word}"
    if len(x) < 3 or not np.all(np.isfinite(y)) or not np.all(np.isfinite(err)):
        return Verdict(UNRESOLVED, f"fewer than 3 points with finite values: no interior {word}",
                       null, "", float("nan")), None
    d = _depths(y, kind)
    i = int(np.argmax(d))
    s = 1.0 if kind == "min" else -1.0
    left = (s * (y[:i] - y[i])) / np.hypot(err[:i], err[i])
    right = (s * (y[i + 1:] - y[i])) / np.hypot(err[i + 1:], err[i])
    zl, zr = float(left.max()), float(right.max())
    sig = float(np.median(err))
    def at(k):
        return extremum_power(effect, sig / math.sqrt(k)) if effect else float("nan")
    pw, k = at(1.0), float("nan")
    alt = (f"a {word} of depth {fmt.format(effect)} ({effect_source})" if effect else
           "none: the source gives no size for the feature")
    pw_text = (f"power {pw:.2f} against {alt}" if math.isfinite(pw) else f"no power ({alt})")
    where = f"x = {fmt.format(x[i])}"
    if zl > 2.0 and zr > 2.0:
        text = (f"{word} at {where}, the curve {'rises' if kind == 'min' else 'falls'} by "
                f"{zl:.1f}σ to its left and {zr:.1f}σ to its right; {pw_text}")
        if expect_at is not None and not (x[i - 1] <= expect_at <= x[i + 1]):
            # elsewhere: it disagrees only where the curve at the source's place is off the
            # extremum's value at the 1 % level (noise moves the deepest point by a step)
            j = int(np.argmin(np.abs(x - expect_at)))
            zj = s * (y[j] - y[i]) / math.hypot(err[j], err[i])
            v = DISAGREES if zj > z_of(P_REJECT) else UNRESOLVED
            return Verdict(v, text + f"; the source puts it at {fmt.format(expect_at)}, outside "
                           f"[{fmt.format(x[i - 1])}, {fmt.format(x[i + 1])}], where the curve "
                           f"is {zj:.1f}σ off the {word}", null, alt, pw, k, at), float(x[i])
        if expect_at is not None:
            text += (f"; the source's {fmt.format(expect_at)} lies between its neighbours "
                     f"{fmt.format(x[i - 1])} and {fmt.format(x[i + 1])}")
        v = AGREES if math.isfinite(pw) and pw >= POWER else UNRESOLVED
        return Verdict(v, text, null, alt, pw, k, at), float(x[i])
    text = (f"no {word} found: the deepest interior point ({where}) differs by {zl:.1f}σ / "
            f"{zr:.1f}σ from the sides; {pw_text}")
    v = DISAGREES if math.isfinite(pw) and pw >= POWER_MISS else UNRESOLVED
    return Verdict(v, text, null, alt, pw, k, at), None


@functools.lru_cache(maxsize=256)
def chi2_isf(p, dof):
    """the χ²_dof value exceeded with probability p"""
    lo, hi = 0.0, max(10.0, 10.0 * dof)
    while chi2_sf(hi, dof) > p:
        hi *= 2.0
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if chi2_sf(mid, dof) > p:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def ncx2_sf(x, dof, lam):
    """P(χ'²_dof(λ) > x): the noncentral χ² as a Poisson(λ/2) mixture of central ones, summed
    over the Poisson weights within 12 standard deviations of their mode"""
    if lam <= 0:
        return chi2_sf(x, dof)
    if x < dof + lam - 12.0 * math.sqrt(2.0 * (dof + 2.0 * lam)):
        return 1.0  # x lies 12 standard deviations below the mean
    h = 0.5 * lam
    w = 12.0 * math.sqrt(h) + 12.0
    total = 0.0
    for j in range(max(0, int(h - w)), int(h + w) + 1):
        total += math.exp(-h + j * math.log(h) - math.lgamma(j + 1)) * chi2_sf(x, dof + 2 * j)
    return min(total, 1.0)


def chi2_power(lam, dof, alpha=P_KEEP):
    """P(a χ² test at level alpha rejects) when the residuals' noncentrality is λ"""
    if not (_finite(lam) and dof >= 1):
        return float("nan")
    return ncx2_sf(chi2_isf(alpha, dof), dof, lam)


def chi2_consistent(residuals, errors, label="residuals", alternative=None, alt_text=""):
    """Values that the source says are zero (or one curve): χ² of residual/error.
    alternative: the residuals the source's alternative would give (its noncentrality
    λ = Σ(alt/err)² sets the power; None: the source names none). Returns (Verdict, p)."""
    r = np.asarray(residuals, float)
    e = np.asarray(errors, float)
    ok = np.isfinite(r) & np.isfinite(e) & (e > 0)
    if alternative is not None:
        a = np.asarray(alternative, float)
        ok &= np.isfinite(a)
    r, e = r[ok], e[ok]
    if len(r) < 1:
        return Verdict(UNRESOLVED, f"no {label} with errors", "", "", float("nan")), float("nan")
    chi2 = float(np.sum((r / e) ** 2))
    dof = len(r)
    p = chi2_sf(chi2, dof)
    text = f"χ² = {chi2:.3g} for {dof} {label}"
    null = f"all {label} are zero"
    if alternative is None:
        return decide(p, float("nan"), null, alt_text or "none named by the source", text,
                       float("nan")), p
    lam = float(np.sum((a[ok] / e) ** 2))

    def at(k):
        return chi2_power(lam * k, dof)
    return decide(p, at(1.0), null, alt_text + f" (noncentrality {lam:.3g})", text, float("nan"),
                  power_at=at), p


def chi2_cov(residuals, cov, label="residuals", alternative=None, alt_text=""):
    """chi2_consistent with a full covariance of the residuals: χ² = rᵀC⁻¹r and the
    alternative's noncentrality aᵀC⁻¹a (the length scaling applies to the whole of C)"""
    r = np.asarray(residuals, float)
    c = np.asarray(cov, float)
    if len(r) < 1 or not np.all(np.isfinite(c)) or not np.all(np.isfinite(r)):
        return Verdict(UNRESOLVED, f"no {label} with errors", "", "", float("nan")), float("nan")
    inv = np.linalg.inv(c)
    chi2 = float(r @ inv @ r)
    dof = len(r)
    p = chi2_sf(chi2, dof)
    text = f"χ² = {chi2:.3g} for {dof} {label} (with their covariance)"
    null = f"all {label} are zero"
    if alternative is None:
        return decide(p, float("nan"), null, alt_text or "none named by the source", text,
                      float("nan")), p
    a = np.asarray(alternative, float)
    lam = float(a @ inv @ a)

    def at(k):
        return chi2_power(lam * k, dof)
    return decide(p, at(1.0), null, alt_text + f" (noncentrality {lam:.3g})", text, float("nan"),
                  power_at=at), p


def cov_inverse(cov, replicas):
    """the guarded inverse of a bootstrap covariance (module docstring); (C⁻¹, the number of
    floored eigenvalues), or (None, why) when it is not usable"""
    c = np.asarray(cov, float)
    n = len(c)
    if n < 1 or not np.all(np.isfinite(c)):
        return None, "the covariance has missing entries"
    if not replicas or replicas <= n + 2:
        return None, f"{replicas} bootstrap replicas do not resolve a covariance of {n} estimates"
    d = np.sqrt(np.diag(c))
    if not np.all(d > 0):
        return None, "an estimate without variance"
    w, v = np.linalg.eigh(c / np.outer(d, d))
    floor = n / replicas
    low = int(np.sum(w < floor))
    w = np.maximum(w, floor)
    inv = (v / w) @ v.T / np.outer(d, d)
    return inv * (replicas - n - 2) / (replicas - 1), low


def without_covariance(v, what="β̂ of different runs"):
    """a verdict from errors taken as independent where the estimates are correlated: an
    agreement becomes not resolved (module docstring)"""
    note = (f" (the {what} are correlated and no covariance was shipped: their errors are "
            "taken as independent, which can make the test lenient, so it cannot agree)")
    if v.verdict == AGREES:
        v.verdict = UNRESOLVED
    v.reason += note
    return v


def offset_test(base, groups, y, e, alt=None, inv=None):
    """Does a constant offset per group (all but the first) lower χ² beyond the nuisance terms
    of `base` (an n × p design: a smooth curve, or a fit's linearized parameters)? Returns
    (Δχ², dof, λ): Δχ² ~ χ²_dof when the groups share one curve; λ the noncentrality of the
    noiseless `alt` (None: nan). inv: the inverse covariance of y (generalised least squares;
    None: independent errors e)."""
    base = np.asarray(base, float).reshape(len(y), -1)
    names = list(dict.fromkeys(groups))
    g = np.array([[1.0 if gi == n else 0.0 for n in names[1:]] for gi in groups]).reshape(len(y), -1)
    full = np.hstack([base, g])
    # whitening: ‖W v‖² = vᵀC⁻¹v
    W = np.diag(1.0 / np.asarray(e, float)) if inv is None else np.linalg.cholesky(inv).T

    def chi(design, v):
        c, *_ = np.linalg.lstsq(W @ design, W @ v, rcond=None)
        return float(np.sum((W @ (v - design @ c)) ** 2))
    y = np.asarray(y, float)
    d = chi(base, y) - chi(full, y)
    lam = float("nan") if alt is None else chi(base, np.asarray(alt, float)) - chi(full, np.asarray(alt, float))
    return d, len(names) - 1, lam


def feature_test(p, lam, dof, null, alt_text, text):
    """a claim that a χ² statistic rejects its null (a feature exists): p of the null, λ the
    noncentrality of the source's feature at this length"""
    def at(k):
        return chi2_power(lam * k, dof) if lam is not None else float("nan")
    return decide(p, at(1.0), null, alt_text, text, float("nan"), feature=True,
                  power_at=at if lam is not None else None)


def focused_test(full, full_dof, part, part_dof, lam, null, alt_text, text):
    """a χ² of every residual (any departure: `full` for full_dof) beside its part along the
    source's alternative (`part` for part_dof, the most powerful against it; λ that
    alternative's noncentrality), Bonferroni over the two: agrees when both keep the null at
    2.5 % and the part had ≥ 80 % power at 2.5 %; disagrees when either rejects at 0.5 %.
    The part carries few degrees of freedom, so data lying exactly on the alternative give a
    part of λ and never agree; a full χ² of many runs alone would let them."""
    p = min(1.0, 2.0 * min(chi2_sf(full, full_dof), chi2_sf(part, part_dof)))

    def at(k):
        return chi2_power(lam * k, part_dof, P_KEEP / 2) if lam is not None else float("nan")
    text = (f"{text}; χ² = {full:.3g} for {full_dof} (every residual) and {part:.3g} for "
            f"{part_dof} (along the alternative), Bonferroni over the two")
    return decide(p, at(1.0), null, alt_text + (f" (noncentrality {lam:.3g})" if lam is not None
                                                else ""), text, float("nan"),
                  power_at=at if lam is not None else None)


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


def _betacf(a, b, x):
    """continued fraction of the regularized incomplete beta function (Lentz)"""
    c, d = 1.0, 1.0 - (a + b) * x / (a + 1.0)
    d = 1.0 / (d if abs(d) > 1e-300 else 1e-300)
    h = d
    for m in range(1, 1000):
        for num in (m * (b - m) * x / ((a + 2 * m - 1) * (a + 2 * m)),
                    -(a + m) * (a + b + m) * x / ((a + 2 * m) * (a + 2 * m + 1))):
            d = 1.0 + num * d
            d = 1.0 / (d if abs(d) > 1e-300 else 1e-300)
            c = 1.0 + num / c
            c = c if abs(c) > 1e-300 else 1e-300
            h *= d * c
        if abs(d * c - 1.0) < 1e-15:
            break
    return h


def t_sf2(t, dof):
    """P(|T_dof| > t), Student's t: the regularized incomplete beta I_{ν/(ν+t²)}(ν/2, 1/2); the
    normal law once ν is so large that ν/(ν+t²) rounds to 1 (the two then agree to < 10⁻⁹)"""
    x = dof / (dof + t * t)
    a, b = 0.5 * dof, 0.5
    if x <= 0:
        return 0.0
    if dof > 1e8 or x >= 1.0:
        return 2.0 * (1.0 - phi(abs(t)))
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b)
                     + a * math.log(x) + b * math.log1p(-x))
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _betacf(a, b, x) / a
    return 1.0 - front * _betacf(b, a, 1.0 - x) / b


def f_sf(f, d1, d2):
    """P(F > f) for Fisher's F of (d1, d2) degrees of freedom: I_{d2/(d2+d1 f)}(d2/2, d1/2)"""
    if not f > 0:
        return 1.0
    x = d2 / (d2 + d1 * f)
    a, b = 0.5 * d2, 0.5 * d1
    front = math.exp(math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b)
                     + a * math.log(x) + b * math.log1p(-x))
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _betacf(a, b, x) / a
    return 1.0 - front * _betacf(b, a, 1.0 - x) / b


def groups_consistent(groups, label="groups"):
    """Groups of independent repeats (a start's seeds) whose means the source says are equal:
    one-way analysis of variance, the scatter between the groups' means against the scatter of
    the repeats within them (F of K − 1 and Σ(n_k − 1) degrees of freedom), which needs no
    error of a single repeat. The source names no alternative: no power. Returns (Verdict, p)."""
    g = [np.asarray(x, float) for x in groups]
    k, n = len(g), sum(len(x) for x in g)
    d1, d2 = k - 1, n - k
    if k < 2 or d2 < 1:
        return Verdict(UNRESOLVED, f"{label}: fewer than two groups or no repeats", "", "",
                       float("nan")), float("nan")
    mean = np.concatenate(g).mean()
    between = sum(len(x) * (x.mean() - mean) ** 2 for x in g) / d1
    within = sum(((x - x.mean()) ** 2).sum() for x in g) / d2
    f = between / within if within > 0 else math.inf
    p = f_sf(f, d1, d2) if math.isfinite(f) else 0.0
    text = f"F = {f:.3g} for {d1} and {d2} degrees of freedom ({label})"
    return decide(p, float("nan"), f"every {label} has the same mean", "none named by the source",
                  text, float("nan")), p

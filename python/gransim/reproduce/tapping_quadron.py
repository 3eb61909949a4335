"""The ideal-quadron fit that every Edwards claim of the tapping report uses: the analysis' fit
of φ̄ against φ̄_quadron(β̂ + β₀) (eq. (26)), refined by one generalised least-squares step with
the bootstrap covariance of the β̂ across runs where the analysis shipped it, so that quadron-a,
the β(φ̄) chart and σ_φ(φ̄) of eq. (17) all read one N z̄/V_g with one error."""
import math

import numpy as np

from .tapping_data import quadron_phi
from .verdicts import cov_inverse

# "The relative deviation of the obtained fitting parameters is smaller than 2%" (section V):
# the precision the paper gives its fit, and so the smallest protocol dependence it would see
A_PAPER, A_PREC = 556.51, 0.02


def _fit(st):
    """the quadron fit over every run: the joint multiple-histogram β̂ where it converged"""
    fits = st.quadron.get("fits", {})
    for name in ("joint", "all"):
        f = fits.get(name)
        if f and f.get("converged"):
            return name, f
    return None, None


def _groups_of(st):
    from .tapping import _groups  # the protocol and branch of each run, as the stress claim
    return _groups(st)


def limits(st):
    """(φ_rlp, φ_rcp) of the fit"""
    return (st.quadron.get("phi_rlp", 0.81), st.quadron.get("phi_rcp", 0.855))


def curve_points(st, name, a, b0):
    """each run with a valid β̂ beside the curve (a, b0): ({group: [(φ̄ − φ_quadron, error,
    the residual if the run lay on a curve A_PREC off, (∂φ/∂a, ∂φ/∂β₀), label, φ̄'s error,
    ∂φ/∂β̂)]}, {label: (β̂, its error)})"""
    lim = limits(st)
    use_joint = name == "joint"
    mult = {r["label"]: r for r in st.beta_multi}
    grp = _groups_of(st)
    groups, bh_of = {}, {}
    for r in st.summary:
        m = mult.get(r["label"])
        if m is None or not (m["joint_valid" if use_joint else "direct_valid"] == 1):
            continue
        bh = m["joint_dbeta" if use_joint else "direct_dbeta"]
        be = m["joint_dbeta_err" if use_joint else "direct_dbeta_err"]
        try:
            pf = quadron_phi(bh + b0, a, *lim)
            dp = (quadron_phi(bh + b0 + 1.0, a, *lim) - pf)
            # the smallest protocol dependence the paper would see: its 2 % between fits
            alt = quadron_phi(bh + b0, a * (1 + A_PREC), *lim) - pf
            da = (quadron_phi(bh + b0, a * 1.001, *lim)
                  - quadron_phi(bh + b0, a * 0.999, *lim)) / (0.002 * a)
            db = (quadron_phi(bh + b0 + 10.0, a, *lim)
                  - quadron_phi(bh + b0 - 10.0, a, *lim)) / 20.0
        except (ZeroDivisionError, ValueError, OverflowError):
            continue
        e = math.hypot(r["phi_err"], dp * (be if math.isfinite(be) else 0.0))
        groups.setdefault(grp[r["label"]], []).append((r["phi_mean"] - pf, e, alt, (da, db),
                                                       r["label"], r["phi_err"], dp))
        bh_of[r["label"]] = (bh, be)
    return groups, bh_of


def residual_cov_inverse(st, name, pts):
    """the inverse covariance of the residuals pts (curve_points' tuples): φ̄'s own error beside
    the β̂ covariance carried through the curve; (None, why) where no beta_cov.csv is shipped"""
    ref = st.info.get("reference")
    cb = st.beta_cov([f"joint:{x[4]}" if name == "joint" else f"direct:{ref}:{x[4]}"
                      for x in pts])
    if cb is None:
        return None, "no beta_cov.csv"
    dp = np.array([x[6] for x in pts])
    return cov_inverse(np.diag([x[5] ** 2 for x in pts]) + np.outer(dp, dp) * cb, st.replicas)


def gls_step(resid, jac, inv):
    """(δa, δβ₀) and their covariance: one generalised least-squares step from a fit whose
    residuals φ̄ − φ_quadron are resid (Jacobian jac in (a, β₀), inverse covariance inv)"""
    cov_p = np.linalg.inv(jac.T @ inv @ jac)
    return cov_p @ jac.T @ inv @ resid, cov_p


def quadron_estimate(st):
    """the fit the claims read: {name, a, a_err, beta0, gls, how} with gls True where one
    generalised least-squares step with the β̂ covariance refined the analysis' fit (how says
    so), else the analysis' own a ± a_err; None without a converged fit"""
    name, fit = _fit(st)
    if fit is None:
        return None
    est = {"name": name, "a": fit["a"], "a_err": fit.get("a_err", float("nan")),
           "beta0": fit["beta0"], "gls": False, "how": ""}
    groups, _ = curve_points(st, name, fit["a"], fit["beta0"])
    pts = [x for vals in groups.values() for x in vals]
    if len(pts) <= 2:
        return est
    inv, why = residual_cov_inverse(st, name, pts)
    if inv is None:
        est["how"] = why
        return est
    step, cov_p = gls_step(np.array([x[0] for x in pts]), np.array([x[3] for x in pts]), inv)
    est.update(a=fit["a"] + float(step[0]), a_err=float(math.sqrt(cov_p[0, 0])),
               beta0=fit["beta0"] + float(step[1]), gls=True,
               how=f"generalised least squares with the bootstrap covariance of the β̂ "
                   f"({st.replicas} replicas; {why} eigenvalues floored)")
    return est

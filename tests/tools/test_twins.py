"""Falsification twins of the reproduction's verdict rules: for each kind of claim, synthetic
statistics whose answer is known exactly (the ideal quadron's φ̄(β) and σ_φ(φ̄), Gaussian decoys
with the same moments, curves with and without the source's feature), drawn at the errors of
series from 50 to 10⁴ taps. A claim that is false by the smallest effect its source would call a
failure may agree at most 1 − 0.80 of the time (the power rule), and at once when measured
without noise never; a true claim may disagree at most 1 % of the time, and never without
noise. Also: the power table in docs/reproduction regenerates identically.
Run: python3 -m unittest tests/tools/test_twins.py"""
import os
import sys
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(ROOT, "python"))

from gransim.reproduce.verdicts import (AGREES, DISAGREES, below_bound, chi2_consistent,  # noqa: E402
                      compare_value, cov_inverse, extremum, feature_test, chi2_sf, t_sf2,
                      without_covariance)
from gransim.reproduce.tapping_data import quadron_phi  # noqa: E402
from gransim.reproduce.tapping_edwards import (conditional_err, gauss_curvature, gauss_dbeta,  # noqa: E402
                             gauss_dlnz_excess, one_curve_test, quadron_sigma,
                             two_refs_verdict)
from gransim.reproduce.tapping_quadron import A_PREC, gls_step  # noqa: E402

REPS = 200
V_G, A = 0.1336, 556.51
# a binomial allowance on REPS draws: 3 standard deviations above the rule's rate
SLACK = 3 * np.sqrt(0.2 * 0.8 / REPS)


def rates(draw):
    """fractions of agrees and disagrees over REPS seeded draws"""
    out = [draw(np.random.default_rng(s)).verdict for s in range(REPS)]
    return out.count(AGREES) / REPS, out.count(DISAGREES) / REPS


def quadron_runs(betas):
    """the ideal quadron sampled exactly: φ̄(β) and σ_φ(φ̄) by eqs. (26), (17)"""
    phi = np.array([quadron_phi(b, A) for b in betas])
    return phi, np.array([quadron_sigma(p, A, V_G) for p in phi])


class Twin(unittest.TestCase):
    def assert_rules(self, true, false, noiseless_true=None, noiseless_false=None):
        a, d = rates(true)
        self.assertLessEqual(d, 0.01 + 3 * np.sqrt(0.01 / REPS), "true claims disagree too often")
        a, d = rates(false)
        self.assertLessEqual(a, 0.2 + SLACK, "false claims agree too often")
        if noiseless_true is not None:
            self.assertNotEqual(noiseless_true.verdict, DISAGREES, noiseless_true.reason)
        if noiseless_false is not None:
            self.assertNotEqual(noiseless_false.verdict, AGREES, noiseless_false.reason)


class ValueClaims(Twin):
    """quadron-a, rot-levels, rot-crossover, xi2, xi-m, D_f, α: a number with a stated precision"""

    def test_at_every_length(self):
        src, tol, alt = 0.821, 0.0005, 0.001
        for n in (50, 200, 1000, 2500, 10000):
            err = 0.003 / np.sqrt(n)
            self.assert_rules(
                lambda r: compare_value(src + r.normal(0, err), err, src, tolerance=tol,
                                        alternative=alt),
                lambda r: compare_value(src + alt + r.normal(0, err), err, src, tolerance=tol,
                                        alternative=alt),
                compare_value(src, err, src, tolerance=tol, alternative=alt),
                compare_value(src + alt, err, src, tolerance=tol, alternative=alt))


class BoundClaims(Twin):
    """halves-mean, halves-sigma, protocol-fits, reference-overlap: a value below a bound"""

    def test_at_every_length(self):
        for n in (50, 200, 1000, 2500, 10000):
            err = 2e-3 / np.sqrt(n)
            self.assert_rules(lambda r: below_bound(abs(r.normal(0, err)), err, 1e-4),
                              lambda r: below_bound(1e-4 + r.normal(0, err), err, 1e-4),
                              below_bound(0.0, err, 1e-4), below_bound(1e-4, err, 1e-4))


class EdwardsClaims(Twin):
    """q-linear and lnz: Edwards' ensemble (Q exactly linear) against Gaussian decoys with the
    same moments (App. A: their Q has the curvature of eq. A1)"""

    def test_q_linear_against_the_gaussian_decoy(self):
        phi, sig = quadron_runs([2e4, 2.6e4, 3.2e4])
        ref = 1
        g = np.array([gauss_curvature(phi[k], sig[k], phi[ref], sig[ref]) for k in (0, 2)])
        for n in (50, 200, 1000, 2500, 10000):
            e = np.full(2, 8.5e4 * np.sqrt(215 / n))  # the curvature error of the standard run, scaled
            self.assert_rules(
                lambda r: chi2_consistent(r.normal(0, e), e, alternative=g)[0],
                lambda r: chi2_consistent(g + r.normal(0, e), e, alternative=g)[0],
                chi2_consistent(np.zeros(2), e, alternative=g)[0],
                chi2_consistent(g, e, alternative=g)[0])

    def test_sigma_phi_one_curve_against_a_protocol_two_percent_off(self):
        phi, sig = quadron_runs(np.linspace(1.5e4, 3.5e4, 8))
        off = np.array([quadron_sigma(p, A * 1.02, V_G) for p in phi[4:]]) - sig[4:]
        alt = np.concatenate([np.zeros(4), off])
        for n in (200, 2500, 10000, 1e5):
            e = 0.3 * sig / np.sqrt(n)  # the error of a standard deviation from n/2 independent taps
            self.assert_rules(
                lambda r: chi2_consistent(r.normal(0, e), e, alternative=alt)[0],
                lambda r: chi2_consistent(alt + r.normal(0, e), e, alternative=alt)[0],
                chi2_consistent(np.zeros(8), e, alternative=alt)[0],
                chi2_consistent(alt, e, alternative=alt)[0])


def one_curve_fixture():
    """twelve runs in three groups on the ideal quadron: the groups, the fit's Jacobian (N z̄/V_g,
    β₀) and each group's alternative (its runs on a curve with N z̄/V_g 2 % off)"""
    b0 = 1.9e4
    bh = np.linspace(-6e3, 6e3, 12)
    grp = ["left"] * 4 + ["right"] * 4 + ["rot"] * 4
    phi = np.array([quadron_phi(b + b0, A) for b in bh])
    jac = np.array([[(quadron_phi(b + b0, A * 1.001) - quadron_phi(b + b0, A * 0.999)) / (0.002 * A),
                     (quadron_phi(b + b0 + 10, A) - quadron_phi(b + b0 - 10, A)) / 20] for b in bh])
    off = np.array([quadron_phi(b + b0, A * 1.02) for b in bh]) - phi
    return grp, jac, {g: np.where(np.array(grp) == g, off, 0.0) for g in ("left", "right", "rot")}


class OneCurve(Twin):
    """one-curve: β̂ of three groups on the ideal quadron (true), or one group on a curve with
    N z̄/V_g 2 % off (false), refitted about the shared fit"""

    def test_at_every_length(self):
        grp, jac, alts = one_curve_fixture()
        for n in (200, 1e4, 1e6, 1e8):
            e = np.full(12, 0.003 / np.sqrt(n))
            self.assert_rules(
                lambda r: one_curve_test(grp, r.normal(0, e), e, jac, alts),
                lambda r: one_curve_test(grp, alts["rot"] + r.normal(0, e), e, jac, alts),
                one_curve_test(grp, np.zeros(12), e, jac, alts),
                one_curve_test(grp, alts["rot"], e, jac, alts))


def correlated(n, e, rho=0.9, length=4.0):
    """a covariance of n estimates with error e whose neighbours are strongly correlated (as β̂
    sharing references and the chain are): e²((1 − ρ)I + ρ e^{−|i−j|/length})"""
    i = np.arange(n)
    return e * e * ((1 - rho) * np.eye(n) + rho * np.exp(-np.abs(i[:, None] - i[None, :]) / length))


def bootstrap_inverse(cov, r, replicas=100):
    """the guarded inverse of the covariance a bootstrap of `replicas` draws would estimate
    (r: None for the exact covariance)"""
    if r is None:
        return cov_inverse(cov, 10 ** 9)[0]
    x = r.multivariate_normal(np.zeros(len(cov)), cov, size=replicas)
    return cov_inverse(np.cov(x, rowvar=False), replicas)[0]


class CovariancePath(Twin):
    """one-curve, quadron and two-references with the bootstrap covariance of correlated β̂: the
    noise drawn with the true covariance, the test made with one estimated from 100 replicas
    (as the analysis ships it); and without a covariance no agreement"""

    def test_one_curve_with_correlated_residuals(self):
        grp, jac, alts = one_curve_fixture()
        for n in (200, 1e4, 1e6):
            e = np.full(12, 0.003 / np.sqrt(n))
            cov = correlated(12, e[0])

            def claim(y, r=None):
                noise = 0.0 if r is None else r.multivariate_normal(np.zeros(12), cov)
                return one_curve_test(grp, y + noise, e, jac, alts, bootstrap_inverse(cov, r))
            self.assert_rules(lambda r: claim(np.zeros(12), r), lambda r: claim(alts["rot"], r),
                              claim(np.zeros(12)), claim(alts["rot"]))
            # without the covariance no agreement, whatever the data
            v = without_covariance(one_curve_test(grp, np.zeros(12), e, jac, alts))
            self.assertNotEqual(v.verdict, AGREES, v.reason)

    def test_quadron_a_with_correlated_residuals(self):
        b0 = 1.9e4
        bh = np.linspace(-6e3, 6e3, 12)
        phi = np.array([quadron_phi(b + b0, A) for b in bh])
        jac = np.array([[(quadron_phi(b + b0, A * 1.001) - quadron_phi(b + b0, A * 0.999)) / (0.002 * A),
                         (quadron_phi(b + b0 + 10, A) - quadron_phi(b + b0 - 10, A)) / 20] for b in bh])
        off = np.array([quadron_phi(b + b0, A * (1 + A_PREC)) for b in bh]) - phi
        for n in (200, 1e4, 1e6):
            cov = correlated(12, 0.003 / np.sqrt(n))

            def claim(y, r=None):
                noise = 0.0 if r is None else r.multivariate_normal(np.zeros(12), cov)
                step, cov_p = gls_step(y + noise, jac, bootstrap_inverse(cov, r))
                return compare_value(A + step[0], np.sqrt(cov_p[0, 0]), A,
                                     alternative=A_PREC * A)
            self.assert_rules(lambda r: claim(np.zeros(12), r), lambda r: claim(off, r),
                              claim(np.zeros(12)), claim(off))

    def test_two_references_with_correlated_differences(self):
        n_runs = 8
        ramp = np.linspace(-1.0, 1.0, n_runs)  # a difference that is not constant (App. A, A4)
        for n in (50, 500, 5000, 5e4):
            e = 300.0 / np.sqrt(n)
            cov = correlated(n_runs, e, rho=0.95)
            alt = 20.0 * ramp

            def claim(d, r=None):
                noise = 0.0 if r is None else r.multivariate_normal(np.zeros(n_runs), cov)
                return two_refs_verdict(d + noise, alt, bootstrap_inverse(cov, r), "twin")
            self.assert_rules(lambda r: claim(np.full(n_runs, 5.0), r),
                              lambda r: claim(5.0 + alt, r), claim(np.full(n_runs, 5.0)),
                              claim(5.0 + alt))
            # the errors taken as independent: never agrees, even where the claim holds
            v = without_covariance(two_refs_verdict(np.full(n_runs, 5.0), alt,
                                                    np.eye(n_runs) / e ** 2, "independent"))
            self.assertNotEqual(v.verdict, AGREES, v.reason)

    def test_guard_floors_an_unresolved_direction(self):
        # two estimates correlated at 0.9999: 100 replicas cannot resolve the small direction,
        # so its eigenvalue is floored at n/R and the χ² along it stays finite and modest
        c = np.array([[1.0, 0.9999], [0.9999, 1.0]])
        inv, low = cov_inverse(c, 100)
        self.assertEqual(low, 1)
        r = np.array([1.0, -1.0]) * 0.1
        self.assertLess(float(r @ inv @ r), 0.02 / (2 / 100) + 1e-9)
        self.assertIsNone(cov_inverse(c, 3)[0])  # R ≤ n + 2: no usable covariance


class ProtocolClaims(Twin):
    """sigma-phi and rot-sigma (σ_φ of runs on (17) against one group on the curve of N z̄/V_g
    2 % off, the fit's a drawn with its error), cross-references (β̂ of the ideal quadron are
    additive; Gaussian decoys' are not, App. A, A4) and timestep (no alternative sized: never
    agrees)"""

    def test_sigma_curve(self):
        from gransim.reproduce.tapping_protocols import sigma_of_phi, sigma_verdict
        phi, _ = quadron_runs(np.linspace(1.2e4, 3.5e4, 12))
        grp = ["left"] * 4 + ["right"] * 4 + ["rot"] * 4
        sig = np.array([sigma_of_phi(p, A, V_G) for p in phi])
        off = np.array([sigma_of_phi(p, A * 1.02, V_G) for p in phi])
        bad = np.where(np.array(grp) == "rot", off, sig)
        for sel in (slice(None), slice(8, 12)):  # every run (sigma-phi); rotating g (rot-sigma)
            for n in (200, 3000, 1e4, 1e5):
                e = 0.3 * sig[sel] / np.sqrt(n / 2)  # σ of σ_φ from n/2 independent taps
                a_err = 16.0 * np.sqrt(215 / n)

                def claim(y, r=None):
                    a = A + (r.normal(0, a_err) if r is not None else 0.0)
                    return sigma_verdict(phi[sel], y, e, grp[sel], a, a_err, V_G)[0]
                self.assert_rules(lambda r: claim(sig[sel] + r.normal(0, e), r),
                                  lambda r: claim(bad[sel] + r.normal(0, e), r),
                                  claim(sig[sel]), claim(bad[sel]))

    def test_cross_references(self):
        from gransim.reproduce.tapping_protocols import offsets_test, references_verdict
        betas_true = np.linspace(1.2e4, 3.5e4, 10)
        phi, sig = quadron_runs(betas_true)
        runs = [f"x{i}" for i in range(10)]
        refs = {"neg": 3, "rot": 6}  # the references are runs of the study
        gauss = {(i, j): gauss_dbeta(phi[i], sig[i], phi[j], sig[j], V_G)
                 for i in range(10) for j in refs.values()}
        alts = {"rot": {runs[i]: gauss[i, 3] - gauss[i, 6] for i in range(10)}}

        def claim(kind, e, r=None):
            betas = {}
            for ref, j in refs.items():
                betas[ref] = {}
                for i in range(10):
                    d = betas_true[i] - betas_true[j] if kind == "edwards" else gauss[i, j]
                    if i == j:
                        betas[ref][runs[i]] = (0.0, 0.0)
                    else:
                        betas[ref][runs[i]] = (d + (r.normal(0, e) if r is not None else 0.0), e)
            return references_verdict(offsets_test(betas, "neg", ["rot"])[2], alts)
        for n in (200, 2000, 1e4, 1e6):
            e = 1400.0 * np.sqrt(215 / n)  # β̂'s error of the standard run, scaled
            self.assert_rules(lambda r: claim("edwards", e, r), lambda r: claim("gauss", e, r),
                              claim("edwards", e), claim("gauss", e))

    def test_cross_references_with_covariance(self):
        """the generalised least-squares form: differences drawn with a known covariance that
        correlates them (each shares its run with the others' and the reference's taps)"""
        from gransim.reproduce.tapping_protocols import offsets_test, references_verdict, stacked
        betas_true = np.linspace(1.2e4, 3.5e4, 10)
        phi, sig = quadron_runs(betas_true)
        runs = [f"x{i}" for i in range(10)]
        gauss = {(i, j): gauss_dbeta(phi[i], sig[i], phi[j], sig[j], V_G)
                 for i in range(10) for j in (3, 6)}
        alts = {"rot": {runs[i]: gauss[i, 3] - gauss[i, 6] for i in range(10)}}
        keys = [runs[i] for i in range(10)]
        rho = np.array([[0.6 ** abs(i - j) for j in range(10)] for i in range(10)])
        for n in (200, 2000, 1e4, 1e6):
            e = 1400.0 * np.sqrt(215 / n)
            cov = e * e * (rho + 0.5)  # neighbours in φ̄ correlated, and one shared part

            def claim(kind, r=None):
                d = np.array([betas_true[6] - betas_true[3] if kind == "edwards"
                              else gauss[i, 3] - gauss[i, 6] for i in range(10)])
                if r is not None:
                    d = d + r.multivariate_normal(np.zeros(10), cov)
                rows = [("rot", 0.0, e, 10, [(x, q, e) for x, q in zip(keys, d)])]
                self.assertEqual(stacked(rows)[0], [("rot", x) for x in keys])
                return references_verdict(rows, alts, cov)
            self.assert_rules(lambda r: claim("edwards", r), lambda r: claim("gauss", r),
                              claim("edwards"), claim("gauss"))
        self.assertTrue(callable(offsets_test))

    def test_timestep(self):
        from gransim.reproduce.tapping_timestep import compare, timestep_verdict
        for n in (50, 500, 2500):
            def claim(r, width):
                x = r.normal(0.82, 0.003, n)
                return timestep_verdict([compare(x, r.normal(0.82, 0.003 * width, n))])
            self.assert_rules(lambda r: claim(r, 1.0), lambda r: claim(r, 1.1))
            x = np.random.default_rng(0).normal(0.82, 0.003, n)
            self.assertNotEqual(timestep_verdict([compare(x, x)]).verdict, DISAGREES)
            wide = timestep_verdict([compare(x, 0.82 + 1.1 * (x - 0.82))])
            self.assertNotEqual(wide.verdict, AGREES, wide.reason)


class GaussianPair(unittest.TestCase):
    """App. A's formulas against the exact log-ratio of two Gaussian densities in V = V_g/φ"""

    def test_curvature_slope_and_intercept(self):
        (p1, s1), (p2, s2) = (0.8392, 0.00184), (0.8349, 0.00196)
        v1, v2 = V_G / p1, V_G / p2
        w1, w2 = V_G * s1 / p1 ** 2, V_G * s2 / p2 ** 2

        def q(v):  # ln P₁/P₂ of the two Gaussians in V
            return (-(v - v1) ** 2 / (2 * w1 ** 2) + (v - v2) ** 2 / (2 * w2 ** 2)
                    + np.log(w2 / w1))
        vm, h = 0.5 * (v1 + v2), 1e-5
        slope = (q(vm + h) - q(vm - h)) / (2 * h)
        curv = (q(vm + h) - 2 * q(vm) + q(vm - h)) / h ** 2 / 2
        # Q = −Δβ V + Δ: Δβ = −slope (eq. 39); curvature per (1/φ)² = per V² · V_g²
        self.assertAlmostEqual(gauss_dbeta(p1, s1, p2, s2, V_G) / -slope, 1.0, places=6)
        self.assertAlmostEqual(gauss_curvature(p1, s1, p2, s2) / (curv * V_G ** 2), 1.0, places=4)
        # the tangent's intercept departs from Edwards' −Δβ·(V₁ + V₂)/2 by the decoy's excess
        # (A6): the tangent's intercept; Edwards' −ln Z₁/Z₂ ≈ Δβ·V̄ = −slope·V̄ at the midpoint
        intercept = q(vm) - slope * vm
        excess = intercept - (-slope * vm)
        self.assertAlmostEqual(excess / gauss_dlnz_excess(p1, s1, p2, s2), 1.0, places=6)


class Covariance(unittest.TestCase):
    def test_conditional_error_of_a_correlated_pair(self):
        # Δβ, Δln Z from one line fit: ρ ≈ −1; the residual about the prediction has a small error
        rng = np.random.default_rng(5)
        eb, el, rho, slope = 1383.0, 220.8, -0.99999, -0.1594
        cov = rho * eb * el
        xy = rng.multivariate_normal([0, 0], [[eb ** 2, cov], [cov, el ** 2]], 200000)
        sd = np.std(xy[:, 1] - slope * xy[:, 0])
        self.assertAlmostEqual(conditional_err(eb, el, cov, slope) / sd, 1.0, delta=0.01)
        self.assertLess(conditional_err(eb, el, cov, slope), 0.05 * el)


class FeatureClaims(Twin):
    """neg-minimum, neg-sigma-maximum, stress: a feature of the source's size exists"""
    G = np.array([2, 6, 9, 12, 16, 20, 25, 30], float)

    def test_minimum(self):
        depth = 1e-3
        dip = 0.83 - depth * np.clip(1 - ((self.G - 20) / 12) ** 2, 0, None)
        flat = np.full(len(self.G), 0.83)
        for n in (50, 200, 1000, 10000):
            e = np.full(len(self.G), 0.003 / np.sqrt(n))
            self.assert_rules(
                lambda r: extremum(self.G, dip + r.normal(0, e), e, "min", 20, depth)[0],
                lambda r: extremum(self.G, flat + r.normal(0, e), e, "min", 20, depth)[0],
                extremum(self.G, dip, e, "min", 20, depth)[0],
                extremum(self.G, flat, e, "min", 20, depth)[0])

    def test_stress_offsets(self):
        from gransim.reproduce.tapping import stress_offsets
        x = np.linspace(0.812, 0.845, 12)
        grp = ["a"] * 6 + ["b"] * 6
        smooth = 0.5 + 3 * (x - 0.83) + 40 * (x - 0.83) ** 2
        step = np.array([0.0] * 6 + [0.01] * 6)

        def test(y, e):
            dchi, dof, lam = stress_offsets(x, grp, {"S": (y, e)}, 0.01)
            return feature_test(chi2_sf(dchi, dof), lam, dof, "", "", "")
        for n in (50, 500, 5000):
            e = np.full(12, 0.05 / np.sqrt(n))
            self.assert_rules(lambda r: test(smooth + step + r.normal(0, e), e),
                              lambda r: test(smooth + r.normal(0, e), e),
                              test(smooth + step, e), test(smooth, e))


class Segregation(unittest.TestCase):
    def test_no_drift_rarely_rejected(self):
        rej = 0
        for s in range(REPS):
            d = np.random.default_rng(s).normal(0, 3.0, 13)
            rej += t_sf2(abs(d.mean()) / (d.std(ddof=1) / np.sqrt(13)), 12) < 0.01
        self.assertLessEqual(rej / REPS, 0.01 + 3 * np.sqrt(0.01 / REPS))


class PowerTable(unittest.TestCase):
    def test_regenerates(self):
        sys.path.insert(0, os.path.join(ROOT, "tools"))
        import power_table
        docs = os.path.join(ROOT, "docs", "reproduction")
        with open(os.path.join(docs, "power.md")) as f:
            shipped = f.read()
        self.assertEqual(power_table.document(docs), shipped)


if __name__ == "__main__":
    unittest.main()

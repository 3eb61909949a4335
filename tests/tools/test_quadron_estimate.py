"""A tapping report's quadron claims read one ideal-quadron N z̄/V_g: quadron-a, σ_φ(φ̄) of
eq. (17) (sigma-phi, rot-sigma) and the β(φ̄) chart all take gransim.reproduce.tapping_quadron's
estimate, the generalised least-squares one where the β̂ covariance is shipped and the analysis'
own fit where it is not.
Run: python3 -m unittest tests/tools/test_quadron_estimate.py"""
import os
import shutil
import sys
import tempfile
import unittest

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "python"))

from gransim.reproduce import tapping  # noqa: E402
from gransim.reproduce.tapping_data import Study  # noqa: E402
from gransim.reproduce.tapping_quadron import gls_step, quadron_estimate  # noqa: E402

STANDARD = os.path.join(ROOT, "docs", "reproduction", "tapping-standard")


def claims_of(folder, drop_cov=False):
    """the claims and the estimate from a copy of a report's analysis tables"""
    tmp = tempfile.mkdtemp(prefix="gs-quadron-")
    shutil.copytree(os.path.join(folder, "analysis"), os.path.join(tmp, "analysis"))
    os.makedirs(os.path.join(tmp, "charts"))
    if drop_cov:
        os.remove(os.path.join(tmp, "analysis", "beta_cov.csv"))
    try:
        _, _, claims, _ = tapping.claims(tmp, "standard")
        return {c.id: c for c in claims}, quadron_estimate(Study(tmp)), Study(tmp)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


class OneEstimate(unittest.TestCase):
    def test_every_claim_reads_the_generalised_least_squares_value(self):
        if not os.path.exists(os.path.join(STANDARD, "analysis", "beta_cov.csv")):
            self.skipTest("the standard report ships no β̂ covariance")
        c, est, st = claims_of(STANDARD)
        self.assertTrue(est["gls"])
        fit = st.quadron["fits"][est["name"]]
        # the step moves the fit: a test that would pass on the analysis' own value proves nothing
        self.assertGreater(abs(est["a"] - fit["a"]), 0.5 * est["a_err"])
        self.assertGreater(est["a_err"], fit["a_err"])  # correlated β̂ carry less information
        self.assertEqual(c["quadron-a"].values["a"], est["a"])
        self.assertEqual(c["quadron-a"].values["beta0"], est["beta0"])
        text = f"N z̄/V_g = {est['a']:.0f} ± {est['a_err']:.0f} m⁻²"
        for cid in ("sigma-phi", "rot-sigma"):
            self.assertIn(text, c[cid].reason, cid)
            self.assertNotIn(f"N z̄/V_g = {fit['a']:.0f} ", c[cid].reason, cid)
        # lnz's prediction comes from the analysis' fit to the direct β̂, and it says which
        direct = st.quadron["fits"]["all"]
        self.assertIn(f"the fit to the direct β̂: N z̄/V_g = {direct['a']:.0f} ±",
                      c["lnz"].measured)

    def test_without_the_covariance_the_analysis_fit_is_read_and_nothing_agrees(self):
        c, est, st = claims_of(STANDARD, drop_cov=True)
        fit = st.quadron["fits"][est["name"]]
        self.assertFalse(est["gls"])
        self.assertEqual((est["a"], est["a_err"], est["beta0"]),
                         (fit["a"], fit["a_err"], fit["beta0"]))
        self.assertEqual(c["quadron-a"].values["a"], fit["a"])
        self.assertIn(f"N z̄/V_g = {fit['a']:.0f} ± {fit['a_err']:.0f} m⁻²", c["sigma-phi"].reason)
        self.assertNotEqual(c["quadron-a"].verdict, "agrees")


class Step(unittest.TestCase):
    def test_a_linear_model_is_solved_in_one_step(self):
        # residuals exactly J·δ with correlated weights: one step recovers δ and its covariance
        rng = np.random.default_rng(7)
        jac = rng.normal(size=(12, 2))
        m = rng.normal(size=(12, 12))
        cov = m @ m.T + 12 * np.eye(12)
        inv = np.linalg.inv(cov)
        delta, cov_p = gls_step(jac @ np.array([3.0, -2.0]), jac, inv)
        np.testing.assert_allclose(delta, [3.0, -2.0], rtol=1e-12)
        np.testing.assert_allclose(cov_p, np.linalg.inv(jac.T @ inv @ jac), rtol=1e-12)


if __name__ == "__main__":
    unittest.main()

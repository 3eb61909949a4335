"""The verdict logic of `gransim reproduce` on synthetic series with known answers: a curve with
a minimum and one without, values and bounds, χ² consistency, and the powers they rest on. Run: python3 -m unittest tests/tools/test_verdicts.py"""
import math
import os
import sys
import unittest

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "python"))

from gransim.reproduce.verdicts import (AGREES, DISAGREES, UNRESOLVED, below_bound, chi2_consistent,  # noqa: E402
                      chi2_power, chi2_sf, compare_value, extremum, mean_err,
                      power_two_sided, t_sf2, tau_int)

G = np.array([2, 6, 10, 15, 20, 25, 30], float)


def vshape(x, at=20.0, depth=0.006, width=18.0):
    return 0.83 - depth * (1 - ((x - at) / width) ** 2).clip(0)


class Extremum(unittest.TestCase):
    def test_curve_with_a_minimum_where_the_source_says(self):
        v, at = extremum(G, vshape(G), np.full(len(G), 0.0004), "min", expect_at=20, effect=0.006)
        self.assertEqual(v.verdict, AGREES, v.reason)
        self.assertEqual(at, 20)
        self.assertGreater(v.power, 0.8)

    def test_a_minimum_without_power_against_the_sources_size_is_not_resolved(self):
        v, _ = extremum(G, vshape(G), np.full(len(G), 0.0004), "min", expect_at=20, effect=0.0005)
        self.assertEqual(v.verdict, UNRESOLVED, v.reason)
        self.assertGreater(v.scale, 1.0)

    def test_minimum_elsewhere_disagrees(self):
        v, at = extremum(G, vshape(G, at=6, width=10), np.full(len(G), 0.0002), "min",
                         expect_at=20, effect=0.002)
        self.assertEqual(v.verdict, DISAGREES, v.reason)
        self.assertEqual(at, 6)

    def test_monotonic_curve_precisely_measured_disagrees(self):
        y = 0.84 - 0.0004 * G
        v, at = extremum(G, y, np.full(len(G), 0.0003), "min", expect_at=20, effect=0.003)
        self.assertEqual(v.verdict, DISAGREES, v.reason)
        self.assertIsNone(at)

    def test_minimum_hidden_in_noise_is_not_resolved(self):
        rng = np.random.default_rng(3)
        y = vshape(G) + rng.normal(0, 0.001, len(G))
        v, _ = extremum(G, y, np.full(len(G), 0.005), "min", expect_at=20, effect=0.002)
        self.assertEqual(v.verdict, UNRESOLVED, v.reason)

    def test_no_size_from_the_source_never_decides_a_missing_feature(self):
        v, _ = extremum(G, np.full(len(G), 0.0022), np.full(len(G), 1e-6), "max", expect_at=20)
        self.assertEqual(v.verdict, UNRESOLVED, v.reason)

    def test_too_few_points(self):
        v, _ = extremum([1, 2], [0.8, 0.81], [0.001, 0.001])
        self.assertEqual(v.verdict, UNRESOLVED)


class Values(unittest.TestCase):
    def test_compare_value(self):
        self.assertEqual(compare_value(1.62, 0.005, 1.63, tolerance=0.03, alternative=0.06).verdict,
                         AGREES)
        self.assertEqual(compare_value(1.40, 0.02, 1.63, 0.03).verdict, DISAGREES)
        # kept but with little power against the source's alternative
        self.assertEqual(compare_value(1.62, 0.05, 1.63, alternative=0.06).verdict, UNRESOLVED)
        # the source names no alternative: it cannot agree, only disagree
        self.assertEqual(compare_value(1.63, 0.001, 1.63).verdict, UNRESOLVED)
        self.assertEqual(compare_value(float("nan"), 0.1, 1.63).verdict, UNRESOLVED)

    def test_bound(self):
        self.assertEqual(below_bound(2e-5, 1e-5, 1e-4).verdict, AGREES)
        self.assertEqual(below_bound(5e-4, 1e-4, 1e-4).verdict, DISAGREES)
        self.assertEqual(below_bound(8e-5, 5e-5, 1e-4).verdict, UNRESOLVED)
        # below the bound, but a value at the bound would be told apart from 0 with 64 % only
        v = below_bound(0.0, 1e-4 / 2.0, 1e-4)
        self.assertEqual(v.verdict, UNRESOLVED, v.reason)


class Power(unittest.TestCase):
    def test_textbook_values(self):
        # 80 % power at 5 % two-sided: effect/σ = 1.960 + 0.8416; χ²₁ noncentrality its square
        self.assertAlmostEqual(power_two_sided(2.8016, 1.0), 0.80, places=3)
        self.assertAlmostEqual(chi2_power(2.8016 ** 2, 1), 0.80, places=3)
        self.assertAlmostEqual(chi2_power(0.0, 4), 0.05, places=6)
        # tabulated: 80 % power of a χ²₂ test at 5 % needs λ = 9.635
        self.assertAlmostEqual(chi2_power(9.635, 2), 0.80, places=3)

    def test_student_t(self):
        # tabulated two-sided: t₁₂ = 3.055 at 1 %, t₃ = 3.182 at 5 %
        self.assertAlmostEqual(t_sf2(3.0545, 12), 0.01, places=4)
        self.assertAlmostEqual(t_sf2(3.1824, 3), 0.05, places=4)


class Chi2(unittest.TestCase):
    def test_survival_function(self):
        # tabulated: P(χ²₁ > 3.841) = 0.05, P(χ²₁₀ > 18.307) = 0.05, P(χ²₄ > 13.277) = 0.01
        self.assertAlmostEqual(chi2_sf(3.841459, 1), 0.05, places=5)
        self.assertAlmostEqual(chi2_sf(18.307038, 10), 0.05, places=5)
        self.assertAlmostEqual(chi2_sf(13.276704, 4), 0.01, places=5)
        self.assertAlmostEqual(chi2_sf(0.5, 30), 1.0, places=9)

    def test_consistent_and_not(self):
        rng = np.random.default_rng(1)
        e = np.full(8, 0.01)
        v, p = chi2_consistent(rng.normal(0, 0.01, 8), e, alternative=np.full(8, 0.02))
        self.assertEqual(v.verdict, AGREES, v.reason)
        v, p = chi2_consistent(rng.normal(0.05, 0.01, 8), e)
        self.assertEqual(v.verdict, DISAGREES, v.reason)
        # no alternative from the source (segregation, T-start, the RFM transient): never agrees
        v, p = chi2_consistent(np.zeros(8), e)
        self.assertEqual(v.verdict, UNRESOLVED, v.reason)


class Series(unittest.TestCase):
    def test_tau_of_ar1(self):
        # AR(1) with ρ = 0.8: τ_int = (1 + ρ)/(2(1 − ρ)) = 4.5
        rng = np.random.default_rng(2)
        x = np.zeros(200000)
        for i in range(1, len(x)):
            x[i] = 0.8 * x[i - 1] + rng.normal()
        self.assertAlmostEqual(tau_int(x), 4.5, delta=0.3)
        self.assertAlmostEqual(tau_int(rng.normal(size=100000)), 0.5, delta=0.05)

    def test_mean_error(self):
        rng = np.random.default_rng(4)
        m, e = mean_err(rng.normal(1.0, 2.0, 40000))
        self.assertAlmostEqual(m, 1.0, delta=4 * e)
        self.assertAlmostEqual(e, 2.0 / math.sqrt(40000), delta=0.15 * e)


if __name__ == "__main__":
    unittest.main()

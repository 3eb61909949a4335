"""The Random Force Model's 2D-fluid and auxiliary-model claims (g-R, moments-phi, alpha-phi,
crossover, spm-alpha, spm-pv, cascade): falsification twins of each verdict rule on synthetic numbers
whose answer is known (a claim false by the smallest effect the thesis would call a failure
agrees at most 1 − 0.80 of the time, a true one disagrees at most 1 %), the fits against exact
curves (P₀ of T.5.32, g(R) = c + A R^(−γ), A/φ moments), and the claims on synthetic folders.
Run: python3 -m unittest tests/tools/test_reproduce_rfm_fluid.py"""
import json
import math
import os
import shutil
import sys
import tempfile
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))

from gransim.reproduce import rfm, rfm_fluid as fl, rfm_models as mo  # noqa: E402
from gransim.reproduce.rfm_data import seed_mean  # noqa: E402
from gransim.reproduce.verdicts import AGREES, DISAGREES, UNRESOLVED  # noqa: E402

REPS = 300
SLACK_AGREE = 3 * np.sqrt(0.2 * 0.8 / REPS)
SLACK_DISAGREE = 3 * np.sqrt(0.01 / REPS)


def rates(draw):
    out = [draw(np.random.default_rng(s)).verdict for s in range(REPS)]
    return out.count(AGREES) / REPS, out.count(DISAGREES) / REPS


class Twin(unittest.TestCase):
    def rules(self, true, false):
        _, d = rates(true)
        self.assertLessEqual(d, 0.01 + SLACK_DISAGREE, "true claims disagree too often")
        a, _ = rates(false)
        self.assertLessEqual(a, 0.2 + SLACK_AGREE, "false claims agree too often")


def seeds(r, truth, n, tau, sigma):
    """a point from n seeds, each off the truth by a seed's own offset and its run's noise"""
    v = truth + r.normal(0, tau, n) + r.normal(0, sigma, n)
    return seed_mean(v, np.full(n, sigma))


class GrTwins(Twin):
    def test_level(self):
        for n, tau, sigma in ((1, 0.0, 0.002), (3, 0.003, 0.001), (3, 0.0, 0.004)):
            with self.subTest(seeds=n, tau=tau, sigma=sigma):
                def draw(truth):
                    return lambda r: fl.gr_verdict(*(lambda s: (s["value"], s["err"], s["dof"]))(
                        seeds(r, truth, n, tau, sigma)))
                self.rules(draw(fl.GR_LEVEL + fl.GR_TOL), draw(fl.GR_LEVEL + fl.GR_ALT))
                self.rules(draw(fl.GR_LEVEL - fl.GR_TOL), draw(fl.GR_LEVEL - fl.GR_ALT))

    def test_level_and_decay_of_an_exact_curve(self):
        R = np.linspace(0.0005, 0.0495, 50)  # bins of 1 mm to R_max = 0.05 m
        g = 0.97 + 0.004 * R ** -0.37
        e = np.full_like(R, 1e-4)
        self.assertAlmostEqual(fl._rmax(R), 0.05)
        lvl, err = fl.gr_level(R, g, e, 0.05)
        m = (R >= 0.025) & (R < 0.05)
        self.assertAlmostEqual(lvl, g[m].mean(), places=12)
        self.assertAlmostEqual(err, 1e-4 / math.sqrt(m.sum()), places=12)
        gam, lo, hi = fl.gr_decay(R, g, e, 0.0125, 0.05)
        self.assertLess(abs(gam - 0.37), 0.021)  # the grid's step is 0.02
        self.assertLessEqual(lo, gam)
        self.assertGreaterEqual(hi, gam)


class MomentTwins(Twin):
    def test_slopes_of_exact_mean_field_moments(self):
        phis = np.array([0.01, 0.03, 0.09])
        y = {m: 0.2 * m / phis for m in fl.ORDERS}
        s = fl.mf_slopes(phis, y, {m: 0.01 * y[m] for m in fl.ORDERS})
        for m in fl.ORDERS:
            self.assertAlmostEqual(s[m][0], -1.0, places=12)

    def test_no_precision_never_agrees(self):
        def draw(slope):
            return lambda r: fl.mf_verdict({m: (slope + r.normal(0, 0.02), 0.02) for m in fl.ORDERS})
        a, d = rates(draw(-1.0))
        self.assertEqual(a, 0.0)
        self.assertLessEqual(d, 0.01 + SLACK_DISAGREE)
        a, d = rates(draw(-0.8))  # 10σ off in every order
        self.assertEqual(a, 0.0)
        self.assertGreater(d, 0.99)


class AlphaPhiTwins(Twin):
    def test_points(self):
        src = [fl.ALPHA_PHI[p] for p in (0.088, 0.177, 0.353, 0.707)]
        for err in (0.01, 0.03):
            with self.subTest(err=err):
                def draw(shift):
                    return lambda r: fl.alpha_phi_verdict(
                        [(a + s * h + r.normal(0, err), err) for (a, h), s in zip(src, shift)], src)
                self.rules(draw([0, 0, 0, 0]), draw([1, 1, 1, 1]))
                self.rules(draw([0, 0, 0, 0]), draw([-1, 1, -1, 1]))

    def test_table_lookup(self):
        self.assertEqual(fl.thesis_alpha(0.0883573)[1], (1.53, 0.08))
        self.assertEqual(fl.thesis_alpha(0.7068583)[1], (1.18, 0.03))
        self.assertIsNone(fl.thesis_alpha(0.5)[0])


class CrossoverTwins(Twin):
    def test_row(self):
        vr, ratio = fl.CROSSOVER[(0.1, 0.1)]
        for err in (0.001, 0.003):
            with self.subTest(err=err):
                def draw(dv, dr):
                    return lambda r: fl.crossover_verdict(vr + dv + r.normal(0, err), err,
                                                          ratio + dr + r.normal(0, 3 * err), 3 * err)
                self.rules(draw(0.0005, -0.0005), draw(0.009, 0.0))
                self.rules(draw(0.0, 0.0), draw(0.0, 0.016))

    def test_fit_recovers_an_exact_p0(self):
        v = np.linspace(-2, 2, 401)
        P = fl.p0(v, 2.0, 0.168, 0.256)
        p, e, chi = fl.fit_p0(v, P, 1e-3 * P)
        np.testing.assert_allclose(p, [2.0, 0.168, 0.256], rtol=1e-5)
        self.assertLess(chi, 1e-6)


class SpmTwins(Twin):
    def test_eq_5_29(self):
        self.assertAlmostEqual(mo.alpha_of(1.63), 3.78 / 3.89, places=3)  # the thesis' arithmetic
        d = 1e-6
        self.assertAlmostEqual(mo.dalpha(1.63), (mo.alpha_of(1.63 + d) - mo.alpha_of(1.63 - d)) / (2 * d),
                               places=6)

    def test_alpha(self):
        def df_for(a):  # the inverse of eq. 5.29
            return (6 - a) / (6 - 3 * a)
        for err in (0.01, 0.03):
            with self.subTest(err=err):
                def draw(a):
                    return lambda r: mo.spm_verdict(df_for(a) + r.normal(0, err), err)[2]
                self.rules(draw(mo.SPM_ALPHA + mo.SPM_TOL), draw(mo.SPM_ALPHA + 2 * mo.SPM_TOL))
                self.rules(draw(mo.SPM_ALPHA - mo.SPM_TOL), draw(mo.SPM_ALPHA - 2 * mo.SPM_TOL))


class SpmPvTwins(Twin):
    def test_slope_of_proportional_tails(self):
        """a fluid whose tail is the model's times 2.5: slope 0 and a = ln 2.5 exactly"""
        v = np.linspace(-2.995, 2.995, 600)
        spm = 1e7 * np.exp(-np.abs(v) / 0.1)
        rfm_ = 2.5 * spm
        rfm_[np.abs(v) < 0.2] *= 3  # a core the model does not describe, outside the tail
        b, e, a, m = mo.tail_slope(v, rfm_, v, spm, np.linspace(0, 3, 121))
        self.assertAlmostEqual(b, 0.0, places=9)
        self.assertGreater(m.sum(), 10)
        self.assertGreater(e, 0)

    def test_no_size_never_agrees(self):
        def draw(slope):
            return lambda r: mo.spm_pv_verdict(slope + r.normal(0, 0.2), 0.2)
        a, d = rates(draw(0.0))
        self.assertEqual(a, 0.0)
        self.assertLessEqual(d, 0.01 + SLACK_DISAGREE)
        a, d = rates(draw(2.0))  # 10σ
        self.assertEqual(a, 0.0)
        self.assertGreater(d, 0.99)


class CascadeTwins(Twin):
    def test_table(self):
        for err in (0.015, 0.04):
            with self.subTest(err=err):
                def draw(off):
                    return lambda r: mo.cascade_verdict(
                        {k: (s + off.get(k, 0) * t + r.normal(0, err), err, None)
                         for k, (s, t) in mo.TABLE_6_2.items()})
                self.rules(draw({}), draw({"ucp": 2}))
                self.rules(draw({k: 1 for k in mo.TABLE_6_2}), draw({"meakin1": -2}))


# ---- the claims on synthetic folders -------------------------------------------------------------

def write_csv(path, cols, rows):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for r in rows:
            f.write(",".join(repr(float(x)) for x in r) + "\n")


class Folders(unittest.TestCase):
    def setUp(self):
        self.d = tempfile.mkdtemp(prefix="gs-rfm-fluid-")
        self.addCleanup(shutil.rmtree, self.d, ignore_errors=True)
        os.makedirs(os.path.join(self.d, "charts"))

    def sweep(self, name, runs, box=0.2):
        a = os.path.join(self.d, "analysis", name)
        for r in runs:
            os.makedirs(os.path.join(a, r["label"]), exist_ok=True)
            with open(os.path.join(a, r["label"], "rfm.json"), "w") as f:
                json.dump({"t_steady": 1.0, "t_end": 6.0, "box": box}, f)
        with open(os.path.join(a, "rfm_summary.json"), "w") as f:
            json.dump({"runs": runs}, f)
        return a

    def plan(self, sweeps):
        with open(os.path.join(self.d, "plan.json"), "w") as f:
            json.dump({"study": "rfm", "budget": "standard", "purpose": "test", "sweeps": sweeps}, f)

    def test_gr_at_l02_is_gated_to_the_thesis_l04(self):
        runs = [dict(label=f"seed={k}", phi=0.5301, eps_n=0.1, eps_t=0.1, particles=3000,
                     structure=dict(D_f=1.63, D_f_err=0.02, k_prime=110.0)) for k in (1, 2, 3)]
        a = self.sweep("structure", runs)
        R = np.linspace(0.000125, 0.049875, 200)
        for k, r in enumerate(runs):
            g = 0.98 + 0.001 * (k - 1) + 0.003 * R ** -0.37
            write_csv(os.path.join(a, r["label"], "gr.csv"), ["R", "g", "g_err", "pairs"],
                      zip(R, g, np.full_like(R, 2e-4), np.full_like(R, 1e6)))
        out = fl.c_gr(self.d, "structure")
        self.assertIn("mean of 3 seeds", out["measured"])
        cond = dict(dimension=2, claims=["g-R"], seeds=[1, 2, 3], starts=["hexagonal"],
                    duration_s=20.0, discard_s=1.0, sampled_s=19.0,
                    points=[dict(phi=0.5301, eps_n=0.1, eps_t=0.1, L=0.2, N=3000)])
        self.plan([dict(name="structure", conditions=cond)])
        row = {c.id: c for c in rfm.claims(self.d, "standard")[2]}["g-R"]
        self.assertEqual(row.verdict, UNRESOLVED)
        self.assertIn("L = 0.2 m where the thesis has 0.4 m", row.reason)

    def test_moments_and_alpha_over_phi(self):
        phis, ns = [0.0884, 0.1767, 0.3534, 0.7069], [500, 1000, 2000, 4000]
        runs = [dict(label=f"count={n}_seed=1", phi=p, eps_n=0.1, eps_t=0.1, particles=n,
                     tail=dict(accepted=True, alpha_lo=fl.thesis_alpha(p)[1][0] - 0.02,
                               alpha_hi=fl.thesis_alpha(p)[1][0] + 0.02, alpha_best=1.2))
                for p, n in zip(phis, ns)]
        a = self.sweep("moments_phi", runs)
        for p, r in zip(phis, runs):
            ms = range(1, 13)
            write_csv(os.path.join(a, r["label"], "moments_components.csv"), ["m", "moment", "error"],
                      [(m, (0.01 / p) ** (m / 3), 0.01 * (0.01 / p) ** (m / 3)) for m in ms])
        out = fl.c_moments_phi(self.d, "moments_phi")
        self.assertEqual(out["verdict"].verdict, UNRESOLVED)  # one point below φ = 0.1
        self.assertIn("1 point(s) below φ = 0.1", out["verdict"].reason)
        self.assertAlmostEqual(out["values"]["rel_m3_phi_max"], 1.0, places=9)
        out = fl.c_alpha_phi(self.d, "moments_phi")
        self.assertEqual(out["verdict"].verdict, AGREES, out["verdict"].reason)

    def test_spm_without_its_model_says_how_to_make_it(self):
        runs = [dict(label=f"seed={k}", phi=0.5301, eps_n=0.1, eps_t=0.1, particles=27000)
                for k in (1, 2, 3)]
        self.sweep("freepath", runs, box=0.6)
        row = {c.id: c for c in rfm.claims(self.d, "standard")[2]}["spm-pv"]
        self.assertEqual(row.verdict, UNRESOLVED)
        self.assertIn("models/spm_seed<K>/walk_spm.csv is missing", row.reason)

    def test_cascade_from_a_model_folder(self):
        row = {c.id: c for c in rfm.claims(self.d, "standard")[2]}["cascade"]
        self.assertEqual(row.verdict, UNRESOLVED)
        self.assertIn("gransim model cascade", row.reason)
        f = os.path.join(self.d, "models", "cascade")
        os.makedirs(f)
        j = {"model": "cascade"}
        for k, (s, t) in mo.TABLE_6_2.items():
            j.update({f"{k}_D_f": s, f"{k}_D_f_err": 0.01, f"{k}_power_law": 1, f"{k}_D2": s})
            write_csv(os.path.join(f, f"cascade_{k}.csv"), ["k", "n", "S", "S_err", "S_exact"],
                      [(2 * math.pi * n, n, 1.0, 0.1, 1.0) for n in (1, 2, 128)])
        with open(os.path.join(f, "model.json"), "w") as fh:
            json.dump(j, fh)
        self.plan([dict(name="structure", conditions=dict(dimension=2, claims=[], points=[]))])
        row = {c.id: c for c in rfm.claims(self.d, "standard")[2]}["cascade"]
        self.assertEqual(row.verdict, AGREES, row.reason)


if __name__ == "__main__":
    unittest.main()

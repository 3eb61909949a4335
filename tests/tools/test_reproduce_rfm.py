"""The Random Force Model report's seeds and conditions: runs of one point from several seeds
(labels ending in seed=K) are grouped into the point, whose value is the mean over the seeds and
whose error the larger of the scatter between seeds and the within-run error; falsification
twins of the tests on such means (Student's t on the seeds' scatter, the starts against the
seeds by analysis of variance): a false claim may agree at most 1 − 0.80 of the time and a true
one disagree at most 1 %; and a claim whose runs miss the thesis' conditions (plan.json's
sweeps[].conditions) is not resolved, saying what is missing.
Run: python3 -m unittest tests/tools/test_reproduce_rfm.py"""
import json
import os
import shutil
import sys
import tempfile
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "python"))
sys.path.insert(0, HERE)

from gransim.reproduce import rfm  # noqa: E402
from gransim.reproduce.rfm_conditions import gate, misses, sweep_for  # noqa: E402
from gransim.reproduce.rfm_data import _runs, seed_mean  # noqa: E402
from gransim.reproduce.verdicts import (AGREES, DISAGREES, UNRESOLVED, Verdict,  # noqa: E402
                                        chi2_consistent, compare_value, groups_consistent)

import temperature_blocks  # noqa: E402
from gransim.reproduce.batch import batch_err, normal_score  # noqa: E402

REPS = 400
SLACK_AGREE = 3 * np.sqrt(0.2 * 0.8 / REPS)
SLACK_DISAGREE = 3 * np.sqrt(0.01 / REPS)
SRC, TOL, ALT = 1.63, 0.03, 0.06  # D_f from S(k): the thesis' 1.63 ± 0.03, a failure at 0.06


def seed_verdict(r, truth, seeds, tau, sigma):
    """a point from `seeds` runs: each run off the truth by a seed's own offset (scatter tau,
    which the within-run error sigma does not see) and its within-run noise"""
    v = truth + r.normal(0, tau, seeds) + r.normal(0, sigma, seeds)
    s = seed_mean(v, np.full(seeds, sigma))
    return compare_value(s["value"], s["err"], SRC, tolerance=TOL, alternative=ALT, dof=s["dof"])


def rates(draw):
    out = [draw(np.random.default_rng(s)).verdict for s in range(REPS)]
    return out.count(AGREES) / REPS, out.count(DISAGREES) / REPS


class SeedMean(unittest.TestCase):
    def test_one_seed_is_the_run(self):
        s = seed_mean([1.5], [0.02])
        self.assertEqual((s["value"], s["err"], s["seeds"], s["dof"]), (1.5, 0.02, 1, None))

    def test_several_seeds(self):
        v, e = [1.0, 2.0, 3.0], [0.1, 0.1, 0.1]
        s = seed_mean(v, e)
        self.assertAlmostEqual(s["value"], 2.0)
        self.assertAlmostEqual(s["between"], 1.0 / np.sqrt(3))  # std 1 over √3
        self.assertAlmostEqual(s["within"], np.sqrt(0.03) / 3)
        self.assertEqual((s["err"], s["which"], s["dof"]), (s["between"], "between seeds", 2))
        s = seed_mean([1.0, 1.001, 0.999], [0.1, 0.1, 0.1])
        self.assertEqual((s["which"], s["dof"]), ("within runs", 2))
        self.assertAlmostEqual(s["err"], np.sqrt(0.03) / 3)


class SeedInterval(unittest.TestCase):
    """the 95 % interval a report prints for a mean over seeds is Student's t of n − 1 degrees of
    freedom, the one its verdict uses; a normal ±1.96σ would be 2.2 times too narrow at 3 seeds"""

    def test_interval_of_three_seeds(self):
        from gransim.reproduce.rfm_data import _ci, seed_text
        self.assertEqual(_ci(1.435, 0.0163), "1.435 ± 0.032")  # one run's own error: normal
        self.assertEqual(_ci(1.435, 0.0163, 2), "1.435 ± 0.070")  # t(2) = 4.303
        s = seed_mean([1.432, 1.464, 1.408], [0.011, 0.011, 0.010])
        self.assertIn("95 % scatter between seeds ± 0.07,", seed_text(s))
        self.assertEqual(_ci(s["value"], s["err"], s["dof"]).split(" ± ")[1], "0.070")


class ResolveText(unittest.TestCase):
    def test_quotes_the_runs_of_the_budget_that_ran_them(self):
        """a claim the quick budget should resolve, left open at the standard budget: the standard
        runs are not the quick ones, so the quick runs' description is not quoted for them"""
        at_standard = rfm.resolve_text("full", "standard", "quick", "3 s sampled")
        self.assertEqual(at_standard, "the full budget, its runs longer than the standard budget's")
        at_quick = rfm.resolve_text("standard", "quick", "quick", "3 s sampled")
        self.assertEqual(at_quick,
                         "the standard budget, its runs longer than the quick budget's (3 s sampled)")


class SeedTwins(unittest.TestCase):
    """the value claims on a mean over seeds, at few and more seeds, with the seeds' scatter
    below, at and far above the within-run error"""

    def test_value_claims(self):
        for seeds in (3, 5):
            for tau, sigma in ((0.0, 0.01), (0.005, 0.01), (0.01, 0.01), (0.005, 0.002),
                               (0.02, 0.002)):
                with self.subTest(seeds=seeds, tau=tau, sigma=sigma):
                    _, d = rates(lambda r: seed_verdict(r, SRC + TOL, seeds, tau, sigma))
                    self.assertLessEqual(d, 0.01 + SLACK_DISAGREE, "true claims disagree")
                    a, _ = rates(lambda r: seed_verdict(r, SRC + ALT, seeds, tau, sigma))
                    self.assertLessEqual(a, 0.2 + SLACK_AGREE, "false claims agree")
                    a, _ = rates(lambda r: seed_verdict(r, SRC - ALT, seeds, tau, sigma))
                    self.assertLessEqual(a, 0.2 + SLACK_AGREE, "false claims agree")

    def test_normal_test_on_three_seeds_would_fail(self):
        """the reason for Student's t: the scatter of three seeds taken as a known error makes
        true claims (at the edge of the thesis' tolerance) disagree far more often than 1 %"""
        def normal(r):
            v = SRC + TOL + r.normal(0, 0.02, 3)
            s = seed_mean(v, np.full(3, 0.002))
            return compare_value(s["value"], s["err"], SRC, tolerance=TOL, alternative=ALT)
        _, d = rates(normal)
        self.assertGreater(d, 0.03)

    def test_starts_against_seeds(self):
        """T-start: three starts from three seeds each, the seeds' scatter tau the only noise;
        the source names no alternative, so the test never agrees"""
        def draw(offsets):
            return lambda r: groups_consistent([0.25 + o + r.normal(0, 0.01, 3) for o in offsets],
                                               "starts")[0]
        a, d = rates(draw([0, 0, 0]))
        self.assertEqual(a, 0.0)
        self.assertLessEqual(d, 0.01 + SLACK_DISAGREE)
        a, d = rates(draw([0, 0.03, 0.06]))  # starts 3 and 6 seed-scatters apart
        self.assertEqual(a, 0.0)
        self.assertGreater(d, 0.8)


def summary_run(label, **kw):
    r = dict(label=label, dir=f"sweeps/x/{label}", dimension=2, particles=2000, phi=0.3534,
             eps_n=0.6, eps_t=0.6, samples=1001, T_mean=0.25, T_err=0.001, notes=[])
    r.update(kw)
    return r


class Folder(unittest.TestCase):
    def setUp(self):
        self.d = tempfile.mkdtemp(prefix="gs-rfm-")
        self.addCleanup(shutil.rmtree, self.d, ignore_errors=True)
        os.makedirs(os.path.join(self.d, "charts"))

    def sweep(self, name, runs, info=None):
        a = os.path.join(self.d, "analysis", name)
        for r in runs:
            os.makedirs(os.path.join(a, r["label"]), exist_ok=True)
            with open(os.path.join(a, r["label"], "rfm.json"), "w") as f:
                json.dump(dict(info or {"t_steady": 1.0, "t_end": 11.0}), f)
        with open(os.path.join(a, "rfm_summary.json"), "w") as f:
            json.dump({"runs": runs}, f)

    def plan(self, sweeps):
        with open(os.path.join(self.d, "plan.json"), "w") as f:
            json.dump({"study": "rfm", "budget": "standard", "purpose": "test",
                       "sweeps": sweeps}, f)


REFERENCE = dict(dimension=2, claims=["T-start", "transient", "T-mean-field"],
                 points=[dict(phi=0.35343, eps_n=0.6, eps_t=0.6, L=0.2, N=2000)], seeds=[1, 2, 3],
                 starts=["square", "hexagonal", "uniform"], duration_s=11.0, discard_s=1.0,
                 sampled_s=10.0, runs=9)


class SeedGrouping(Folder):
    def test_labels_without_seed_group_the_runs(self):
        labels = [f"eps_n={e}_count={n}_seed={k}" for e in ("0.1", "0.5") for n in (398, 631)
                  for k in (1, 2, 3)]
        self.sweep("ring", [summary_run(x) for x in labels])
        pts = _runs(self.d, "ring")
        self.assertEqual([p["label"] for p in pts], ["eps_n=0.1_count=398", "eps_n=0.1_count=631",
                                                     "eps_n=0.5_count=398", "eps_n=0.5_count=631"])
        self.assertEqual([p["name"] for p in pts], ["398", "631", "398", "631"])
        self.assertEqual([[q["seed"] for q in p["runs"]] for p in pts], [["1", "2", "3"]] * 4)
        self.assertEqual(pts[0]["runs"][1]["name"], "398 seed 2")

    def test_seed_only_and_single_seed_labels(self):
        self.sweep("structure", [summary_run(f"seed={k}") for k in (1, 2, 3)])
        pts = _runs(self.d, "structure")
        self.assertEqual([(p["name"], len(p["runs"])) for p in pts], [("structure", 3)])
        self.sweep("reference", [summary_run(f"placement={p}") for p in ("square", "uniform")])
        pts = _runs(self.d, "reference")
        self.assertEqual([(p["name"], len(p["runs"])) for p in pts], [("square", 1), ("uniform", 1)])

    def test_T_start_from_seeds(self):
        """three starts from three seeds: each start the mean of its seeds, the claim judged by
        the starts' scatter against the seeds' (no T(t) file: the block errors are taken)"""
        self.plan([dict(name="reference", conditions=REFERENCE)])
        t = {"square": [0.25, 0.26, 0.24], "hexagonal": [0.255, 0.245, 0.25],
             "uniform": [0.24, 0.25, 0.26]}
        self.sweep("reference", [summary_run(f"placement={p}_seed={k + 1}", T_mean=v)
                                 for p, vs in t.items() for k, v in enumerate(vs)])
        r = rfm.c_start(self.d, "reference")
        self.assertIn("each the mean of 3 seeds", r["measured"])
        self.assertIn("0.25", r["measured"])
        self.assertIn("F = ", r["verdict"].reason)
        self.assertEqual(r["verdict"].verdict, UNRESOLVED)  # kept, but the thesis names no alternative
        t["uniform"] = [0.30, 0.301, 0.299]
        self.sweep("reference", [summary_run(f"placement={p}_seed={k + 1}", T_mean=v)
                                 for p, vs in t.items() for k, v in enumerate(vs)])
        self.assertEqual(rfm.c_start(self.d, "reference")["verdict"].verdict, DISAGREES)


class CoarseReference(Folder):
    """T-start and the transient from the 50-ms blocks of T(t) (and the transient's halves from
    the steady samples) against the same claims on every sample (rfm_series.csv, which a report
    used to read): three starts of 11 s sampled every 1 ms, T rising over 50 ms, then correlated
    noise (τ_int 49.5 samples)"""

    def folder(self, drift):
        self.plan([dict(name="reference", conditions=dict(REFERENCE, seeds=[1]))])
        rng, fine, runs = np.random.default_rng(3), {}, []
        for k, p in enumerate(("square", "hexagonal", "uniform")):
            t = np.arange(0, 11_001) * 1e-3
            T = (0.25 + 0.004 * k) * (1 - np.exp(-t / 0.05)) + drift * t
            T += temperature_blocks.ar1(rng, len(t), 0.98, 0.005)
            a = os.path.join(self.d, "analysis", "reference", f"placement={p}")
            os.makedirs(a, exist_ok=True)
            temperature_blocks.write(a, t, T, t >= 1.0, dt=1e-3)
            with open(os.path.join(a, "temperature.csv"), "w") as f:
                f.write("t,T\n" + "".join(f"{x!r},{y!r}\n" for x, y in zip(t[t >= 1.0],
                                                                         T[t >= 1.0])))
            fine[p] = (t, T)
            runs.append(summary_run(f"placement={p}", T_mean=float(T[t >= 1.0].mean()),
                                    T_err=1e-4))
        self.sweep("reference", runs)
        return fine

    def test_T_start_as_from_every_sample(self):
        fine = self.folder(0.0)
        r = rfm.c_start(self.d, "reference")
        T, E, F = [], [], []
        for t, x in fine.values():  # the run's error: batch means of its steady samples
            m, e, f = batch_err(x[t >= 1.0])
            T.append(m)
            E.append(e)
            F.append(f)
        self.assertAlmostEqual(r["values"]["T_mean"], np.mean(T), delta=1e-14)
        self.assertAlmostEqual(r["values"]["T_err"], np.sqrt(np.sum(np.square(E))) / 3, delta=1e-14)
        z = []  # Helmert contrasts of equal weights, each Welch–Satterthwaite t as a normal score
        for k in (1, 2):
            c = np.append(np.full(k, -1.0 / k), 1.0)
            v = (c * E[:k + 1]) ** 2
            t = (c * T[:k + 1]).sum() / np.sqrt(v.sum())
            z.append(normal_score(t, v.sum() ** 2 / (v ** 2 / np.array(F[:k + 1])).sum()))
        v, p = chi2_consistent(z, np.ones(2), label="contrasts between the starts")
        self.assertAlmostEqual(r["values"]["p"], p, delta=1e-12)
        self.assertEqual(r["verdict"].verdict, v.verdict)
        self.assertEqual(r["verdict"].reason.split("; each run")[0], v.reason)

    def test_transient_as_from_every_sample(self):
        """the halves' batch means from the steady samples (temperature.csv) as from every
        sample (rfm_series.csv): the same verdict, χ² and p; the rise from the 50-ms blocks, its
        settling time at a block's resolution"""
        for drift, want in ((0.0, UNRESOLVED), (0.002, DISAGREES)):
            with self.subTest(drift=drift):
                fine = self.folder(drift)
                r = rfm.c_transient(self.d, "reference")
                z, s = [], []
                for p, (t, T) in fine.items():
                    a, b = T[(t >= 1.0) & (t < 6.0)], T[t >= 6.0]
                    self.assertAlmostEqual(r["values"][f"dT_{p}"], a.mean() - b.mean(),
                                           delta=1e-13)
                    (ma, ea, da), (mb, eb, db) = batch_err(a), batch_err(b)
                    e = np.hypot(ea, eb)
                    welch = e ** 4 / (ea ** 4 / da + eb ** 4 / db)
                    z.append(normal_score((ma - mb) / e, welch) * e)
                    s.append(e)
                v, _ = chi2_consistent(z, s, label="differences ⟨T⟩[1 s, mid] − ⟨T⟩[mid, end]")
                self.assertEqual(v.verdict, want)
                self.assertEqual(r["verdict"].verdict, want, r["verdict"].reason)
                self.assertEqual(r["verdict"].reason, v.reason)
                # the rise's end at the resolution of a block (T reaches 90 % at 0.115 s)
                if not drift:
                    self.assertIn("50-ms means stay within 10 % of the last-half mean from "
                                  "0.10 s (square), 0.10 s (hexagonal), 0.10 s (uniform)",
                                  r["measured"])


class Conditions(Folder):
    RING = dict(dimension=1, claims=["xi2", "xi-m"], seeds=[1], starts=[], duration_s=8.0,
                discard_s=1.0, sampled_s=7.0, runs=4,
                points=[dict(phi=0.5, eps_n=0.1, eps_t=1.0, reduced_length=1.0, N=n)
                        for n in (400, 1000, 2500, 4000)])
    N512 = dict(dimension=1, claims=["G1-bisection"], seeds=[1, 2, 3], starts=[],
                duration_s=220.0, discard_s=20.0, sampled_s=200.0, runs=3,
                points=[dict(phi=0.6, eps_n=0.1, eps_t=1.0, reduced_length=1.0, N=512)])

    def test_what_is_missing(self):
        m = misses("G1-bisection", self.RING)
        self.assertIn("N = 400, 1000, 2500, 4000 where the thesis has 512", m)
        self.assertIn("7 s sampled where the thesis needed ≈ 200 s", m)
        self.assertIn("1 s discarded where the thesis discards ≈ 20 s", m)
        self.assertEqual(misses("G1-bisection", self.N512), [])
        self.assertEqual(misses("xi2", dict(self.RING, discard_s=20.0, sampled_s=200.0)), [])
        self.assertEqual(misses("T-start", REFERENCE), [])
        self.assertEqual(misses("T-start", dict(REFERENCE, starts=["hexagonal"])),
                         ["1 start(s) where the claim compares 2 at least"])
        self.assertEqual(misses("T-mean-field", REFERENCE),
                         ["φ = 0.353 where the thesis has φ < 0.1"])
        free = dict(REFERENCE, points=[dict(phi=0.5301, eps_n=0.1, eps_t=0.1, L=0.2, N=3000)])
        self.assertEqual(misses("Df-freepath", free), ["L = 0.2 m where the thesis has 0.6 m"])
        self.assertEqual(misses("Df-Sk", free), [])
        self.assertEqual(misses("Df-Sk", dict(free, points=[dict(free["points"][0], eps_t=1.0)])),
                         ["ε = 0.1/1 where the thesis has 0.1"])
        self.assertEqual(misses("xi2", REFERENCE), ["0 ring size(s) at the thesis' parameters "
                                                    "where the fit needs 2 (a 2D fluid where the "
                                                    "thesis has a 1D ring)",
                                                    "1 s discarded where the thesis discards ≈ 20 s",
                                                    "10 s sampled where the thesis needed ≈ 200 s"])

    def test_conditions_from_the_scenes_where_the_plan_states_none(self):
        """a plan written before it recorded conditions: the runs' scene.toml files give them,
        so a claim made at another box size is still gated"""
        agrees = Verdict(AGREES, "measured 1 ± 0.1", "null", "alt", 0.9)
        self.plan([dict(name="structure", params=[], sets=[])])
        self.assertIs(gate(self.d, "g-R", "structure", agrees)[0], agrees)  # no scene: as before
        run = os.path.join(self.d, "sweeps", "structure", "seed=1")
        os.makedirs(run)
        with open(os.path.join(run, "scene.toml"), "w") as f:
            f.write('[scene]\nduration = 4.0\n[box]\nwidth = 0.2\nheight = 0.2\n'
                    '[rfm]\ndiscard_time = 1.0\n[preparation]\nseed = 1\n'
                    'placement = "hexagonal"\n[[species]]\ncount = 3000\nradius = 0.0015\n'
                    '[[material]]\neps_n = 0.1\neps_t = 0.1\n')
        v, miss = gate(self.d, "g-R", "structure", agrees)
        self.assertEqual(v.verdict, UNRESOLVED)
        self.assertEqual(miss, "L = 0.2 m where the thesis has 0.4 m")
        self.assertIn("at face value: agrees", v.reason)
        # the same system at the thesis' box passes
        with open(os.path.join(run, "scene.toml")) as f:
            text = f.read().replace("0.2", "0.4").replace("3000", "12000")
        with open(os.path.join(run, "scene.toml"), "w") as f:
            f.write(text)
        self.assertIs(gate(self.d, "g-R", "structure", agrees)[0], agrees)

    def test_gate_and_sweep_choice(self):
        agrees = Verdict(AGREES, "measured 1 ± 0.1", "null", "alt", 0.9)
        v, miss = gate(self.d, "G1-bisection", "ring", agrees)  # no plan: as before
        self.assertIs(v, agrees)
        self.assertEqual(miss, "")
        self.plan([dict(name="ring", conditions=self.RING)])
        self.assertEqual(sweep_for(self.d, "G1-bisection", "ring"), "ring")
        v, miss = gate(self.d, "G1-bisection", "ring", agrees)
        self.assertEqual(v.verdict, UNRESOLVED)
        self.assertIn("N = 400, 1000, 2500, 4000 where the thesis has 512", v.reason)
        self.assertIn("at face value: agrees, measured 1 ± 0.1", v.reason)
        self.plan([dict(name="ring", conditions=self.RING),
                   dict(name="ring_n512", conditions=self.N512)])
        self.assertEqual(sweep_for(self.d, "G1-bisection", "ring"), "ring_n512")
        self.assertIs(gate(self.d, "G1-bisection", "ring_n512", agrees)[0], agrees)
        phi = dict(REFERENCE, claims=["moments-phi"], starts=["hexagonal"],
                   points=[dict(phi=p, eps_n=0.1, eps_t=0.1, L=0.2, N=n)
                           for p, n in ((0.0884, 500), (0.1767, 1000))])
        self.plan([dict(name="reference", conditions=REFERENCE),
                   dict(name="moments_phi", conditions=phi)])
        self.assertEqual(sweep_for(self.d, "T-mean-field", "reference"), "moments_phi")
        self.assertEqual(sweep_for(self.d, "T-start", "reference"), "reference")
        self.plan([dict(name="ring", params=[], sets=[])])  # an old plan: no conditions
        self.assertIs(gate(self.d, "xi2", "ring", agrees)[0], agrees)

    def test_report_row_says_what_is_missing(self):
        """claims(): the ring sampled 7 s: ξ₂ is not resolved, and says why"""
        self.plan([dict(name="ring", conditions=self.RING)])
        rows = {c.id: c for c in rfm.claims(self.d, "quick")[2]}
        self.assertEqual(rows["xi2"].verdict, UNRESOLVED)
        v, _ = gate(self.d, "xi2", "ring", Verdict(DISAGREES, "face"))
        self.assertIn("7 s sampled where the thesis needed ≈ 200 s", v.reason)


if __name__ == "__main__":
    unittest.main()

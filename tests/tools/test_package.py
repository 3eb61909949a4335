"""The pure-Python part of the gransim package as a user imports it on their own data, from the
source tree and without the compiled module: the verdict engine on a synthetic AR(1) series with
known answers, a chart drawn from the user's own CSV file, the chart module run as the command
line runs it (python3 -m), and a clear error for what does need the compiled module.
Run: python3 -m unittest tests/tools/test_package.py"""
import json
import os
import subprocess
import sys
import tempfile
import unittest

import numpy as np

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
PACKAGE_DIR = os.path.join(ROOT, "python")
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
PHI = 0.9  # AR(1) coefficient: τ_int = (1 + φ)/(2(1 − φ)) = 9.5 samples, σ² = s²/(1 − φ²)


def ar1(n, mean, s, seed):
    rng = np.random.default_rng(seed)
    x = np.empty(n)
    x[0] = mean
    for i in range(1, n):
        x[i] = mean + PHI * (x[i - 1] - mean) + s * rng.standard_normal()
    return x


def python(code, *args, cwd=None, backend=None):
    """code run by a fresh interpreter that sees only the source tree's package"""
    env = dict(os.environ, PYTHONPATH=PACKAGE_DIR)
    env.pop("MPLBACKEND", None)
    if backend:
        env["MPLBACKEND"] = backend
    return subprocess.run([PYTHON, *code, *args], capture_output=True, text=True, env=env,
                          cwd=cwd, timeout=300)


class Verdicts(unittest.TestCase):
    """verdicts on numbers of one's own, imported as a user does"""

    @classmethod
    def setUpClass(cls):
        sys.path.insert(0, PACKAGE_DIR)
        from gransim.reproduce import verdicts
        cls.v = verdicts

    def test_error_counts_the_correlation(self):
        # 40 series of 4000 samples: the mean τ_int within 15 % of 9.5 (Sokal's window is
        # biased low by a few per cent; the scatter of one estimate is about 10 %), and the
        # standard error it gives matches the scatter of the 40 means within 25 % (χ² with 39
        # degrees of freedom: ±23 % at 2σ)
        s = 0.05
        taus, means, errs = [], [], []
        for seed in range(40):
            x = ar1(4000, 2.0, s, seed)
            taus.append(self.v.tau_int(x))
            m, e = self.v.mean_err(x)
            means.append(m)
            errs.append(e)
        self.assertAlmostEqual(np.mean(taus) / 9.5, 1.0, delta=0.15)
        self.assertAlmostEqual(np.std(means, ddof=1) / np.mean(errs), 1.0, delta=0.25)
        # independent samples would claim an error √(2τ) ≈ 4.4 times too small
        sigma = s / np.sqrt(1 - PHI ** 2)
        self.assertGreater(np.mean(errs), 3.0 * sigma / np.sqrt(4000))

    def test_a_true_value_agrees_and_a_wrong_one_disagrees(self):
        x = ar1(4000, 2.0, 0.05, 4)
        mean, err = self.v.mean_err(x)
        right = self.v.compare_value(mean, err, source=2.0, alternative=0.05)
        self.assertEqual(right.verdict, self.v.AGREES, right.reason)
        self.assertGreater(right.power, 0.99)
        wrong = self.v.compare_value(mean, err, source=2.05, alternative=0.05)
        self.assertEqual(wrong.verdict, self.v.DISAGREES, wrong.reason)
        # without an alternative the test has no power to claim agreement
        blind = self.v.compare_value(mean, err, source=2.0)
        self.assertEqual(blind.verdict, self.v.UNRESOLVED, blind.reason)


class Charts(unittest.TestCase):
    def test_a_chart_of_ones_own_csv_imported_and_as_a_module(self):
        with tempfile.TemporaryDirectory() as d:
            x = ar1(2000, 2.0, 0.05, 1)
            t = 1e-3 * np.arange(len(x))
            np.savetxt(os.path.join(d, "temperature.csv"), np.column_stack([t, x]),
                       delimiter=",", header="t,T", comments="")
            os.mkdir(os.path.join(d, "own"))
            # imported: the importer's backend (here svg, not the Agg a command selects) is left
            # alone, and the PNG written all the same
            code = ("import matplotlib, gransim.charts.rfm as c; "
                    "c.temperature('temperature.csv', 'own'); print(matplotlib.get_backend())")
            p = python(["-c", code], cwd=d, backend="svg")
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual(p.stdout.split()[-1], "svg")
            self.assertGreater(os.path.getsize(os.path.join(d, "own", "temperature.png")), 5000)
            # as `gransim analyze` runs it: every chart of the folder whose data are there
            p = python(["-m", "gransim.charts.rfm", d, "--no-parent"], cwd=d)
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertGreater(os.path.getsize(os.path.join(d, "temperature.png")), 5000)
            self.assertIn("skipped (missing)", p.stdout)  # velocity.csv and the rest


class WithoutTheCompiledModule(unittest.TestCase):
    def test_the_simulation_names_what_is_missing(self):
        code = ("import gransim\n"
                "from gransim import charts, reproduce\n"
                "try:\n    gransim.Simulation\nexcept ImportError as e:\n    print(e)\n")
        with tempfile.TemporaryDirectory() as d:
            p = python(["-c", code], cwd=d)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("gransim.Simulation needs the compiled module gransim._gransim", p.stdout)

    def test_the_report_module_runs_and_checks_its_input(self):
        with tempfile.TemporaryDirectory() as d:
            p = python(["-m", "gransim.reproduce", "--study", "tapping", "--budget", "quick", d],
                       cwd=d)
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        self.assertIn("no analysis here", p.stderr)

class RunCost(unittest.TestCase):
    """a report's run time: each run's CPU time where its run.json keeps it for every session,
    its wall time (which counts whatever else ran beside it) where it does not"""

    def test_cpu_time_where_every_session_has_it(self):
        sys.path.insert(0, PACKAGE_DIR)
        from gransim.reproduce.cli import run_cost
        runs = {"a/s1": {"status": "completed", "sessions": 2, "wall_time_s": 900.0,
                         "cpu_time_s": 300.0, "cpu_time_sessions": 2},
                "a/s2": {"status": "completed", "sessions": 3, "wall_time_s": 800.0,
                         "cpu_time_s": 100.0, "cpu_time_sessions": 1},  # two sessions without
                "b/s1": {"status": "interrupted", "sessions": 1, "wall_time_s": 50.0}}
        with tempfile.TemporaryDirectory() as d:
            for name, rj in runs.items():
                os.makedirs(os.path.join(d, "sweeps", name))
                with open(os.path.join(d, "sweeps", name, "run.json"), "w") as f:
                    json.dump(rj, f)
            core_s, n, by_wall, unfinished = run_cost(d)
        self.assertEqual(n, 3)
        self.assertEqual(by_wall, 2)
        self.assertAlmostEqual(core_s, 300.0 + 800.0 + 50.0)
        self.assertEqual(unfinished, ["b/s1"])

    def test_header_names_how_the_runs_were_counted(self):
        sys.path.insert(0, PACKAGE_DIR)
        from gransim.reproduce.cli import run_time_text
        self.assertEqual(run_time_text(7200, 3, 0),
                         "2.00 core-hours: the CPU times of its 3 runs (one thread each) added up")
        self.assertIn("; 2 of them by their wall times", run_time_text(7200, 3, 2))
        every = run_time_text(3600, 8, 8)
        self.assertIn("the wall times of its 8 runs added up (none kept its CPU time)", every)
        self.assertNotIn("CPU times of", every)


if __name__ == "__main__":
    unittest.main()

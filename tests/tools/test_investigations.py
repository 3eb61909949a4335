"""Twins of the halves test tools/reproduce_investigations.py applies to the long run: synthetic
columns whose answer is known (AR(1) taps of the runs' size and correlation) must not disagree
with the paper's bounds where the columns equal the whole, and must disagree where a column is
offset by the relative 0.0022 the quick budget measured at 2 Hz. Also runs the script on the
shipped folder.
Run: python3 -m unittest tests/tools/test_investigations.py"""
import contextlib
import io
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "python"))

import reproduce_investigations as inv  # noqa: E402
from gransim.reproduce.verdicts import DISAGREES  # noqa: E402



def ar1(rng, n, tau, sd):
    """AR(1) with integrated autocorrelation time tau (in taps) and standard deviation sd"""
    a = (tau - 0.5) / (tau + 0.5)
    x = np.empty(n)
    x[0] = rng.normal(0, sd)
    e = rng.normal(0, sd * math.sqrt(1 - a * a), n)
    for i in range(1, n):
        x[i] = a * x[i - 1] + e[i]
    return x


def quietly(f, *a):
    with contextlib.redirect_stdout(io.StringIO()):
        return f(*a)


class Halves(unittest.TestCase):
    def run_(self, rel_offset, seed):
        rng = np.random.default_rng(seed)
        n = 1500
        whole = 0.82 + ar1(rng, n, 1.5, 0.0012)
        # each column: the whole plus independent noise of the same size, opposite in the other
        d = ar1(rng, n, 1.5, 0.0012)
        left, right = whole * (1 + rel_offset) + d, whole * (1 - rel_offset) - d
        runs = {"h": dict(name="h", protocol="rotating_g", control="2", start="long", taps=n,
                          phi=whole, left=left, right=right)}
        return quietly(inv.halves, runs)

    def test_equal_columns_do_not_disagree(self):
        for seed in range(20):
            v = self.run_(0.0, seed)
            self.assertNotEqual(v[("h", "left")].verdict, DISAGREES)
            self.assertNotEqual(v[("h", "right")].verdict, DISAGREES)

    def test_an_offset_column_disagrees(self):
        for seed in range(5):
            v = self.run_(0.0022, 100 + seed)
            self.assertEqual(v[("h", "left")].verdict, DISAGREES)


class Shipped(unittest.TestCase):
    def test_runs_on_the_kept_series(self):
        # on a copy: the script draws its charts into the folder it reads
        with tempfile.TemporaryDirectory() as tmp:
            folder = os.path.join(tmp, "investigations")
            shutil.copytree(os.path.join(ROOT, "docs", "reproduction", "investigations"), folder)
            out = subprocess.run([sys.executable, os.path.join(ROOT, "tools",
                                                               "reproduce_investigations.py"),
                                  folder], capture_output=True, text=True, check=True).stdout
            self.assertIn("gp2-annealed − gp2-loose", out)
            for chart in ("weak_tap.png", "high_f.png", "halves.png"):
                self.assertTrue(os.path.exists(os.path.join(folder, chart)), chart)
            self.assertIn("## halves, halves-2hz: 1500 of 1500 taps", out)


if __name__ == "__main__":
    unittest.main()

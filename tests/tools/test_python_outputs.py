"""Every CSV a run and `gransim analyze` write opens with pandas.read_csv(path) as it is, with
named, numeric columns (text only where a column holds names); run.json loads with json.load and
holds typed scene values; and the snippets of docs/python.md run on those directories.
Needs GS_BINARY (the gransim executable).
Run: GS_BINARY=build/gransim python3 -m unittest tests/tools/test_python_outputs.py"""
import glob
import json
import os
import re
import shutil
import subprocess
import tempfile
import unittest
import sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tiny_scenes import tiny_tapping  # noqa: E402

import pandas as pd

BINARY = os.environ.get("GS_BINARY", "build/gransim")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TEXT_COLUMNS = {"label", "protocol", "reference", "dir", "status", "file", "species"}

# 40 grains tapped 22 times (analyze needs 20 after the 2 discarded), a few seconds
TAPPING = tiny_tapping(0.5, 22)


def load(path):
    with open(path) as f:
        return json.load(f)


class PythonOutputs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="gs-python-outputs-")
        env = dict(os.environ, OMP_NUM_THREADS="1", GS_PYTHON_DIR=os.path.join(ROOT, "python"))
        scene = os.path.join(cls.tmp, "tiny_tapping.toml")
        with open(scene, "w") as f:
            f.write(TAPPING)
        cls.tap_dir = os.path.join(cls.tmp, "tap")
        cls.rfm_run = os.path.join(cls.tmp, "rfm")
        cls.analysis = os.path.join(cls.tmp, "tap_analysis")
        cls.rfm_analysis = os.path.join(cls.tmp, "rfm_analysis")
        rfm_scene = os.path.join(ROOT, "scenes", "rfm2d_reference.toml")
        for args in (["run", scene, "--out", cls.tap_dir],
                     ["run", rfm_scene, "--out", cls.rfm_run, "--set", "scene.duration=0.03",
                      "--set", "rfm.discard_time=0.01", "--set", "rfm.sample_every=500"],
                     ["analyze", cls.tap_dir, "--out", cls.analysis],
                     ["analyze", cls.rfm_run, "--out", cls.rfm_analysis]):
            p = subprocess.run([BINARY] + args + ["--quiet"] * (args[0] == "run"),
                               capture_output=True, text=True, env=env, timeout=600)
            assert p.returncode == 0, " ".join(args) + "\n" + p.stdout[-3000:] + p.stderr[-3000:]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_every_csv_reads_as_it_is(self):
        files = []
        for d in (self.tap_dir, self.rfm_run, self.analysis, self.rfm_analysis):
            files += glob.glob(os.path.join(d, "**", "*.csv"), recursive=True)
        names = {os.path.basename(f) for f in files}
        for want in ("state.csv", "taps.csv", "series.csv", "rfm_series.csv", "hist_velocity.csv",
                     "temperature.csv", "velocity.csv", "sk.csv", "summary.csv", "kde.csv",
                     "moments_vs_N.csv", "exponents.csv"):
            self.assertIn(want, names)
        for f in files:
            with self.subTest(csv=os.path.relpath(f, self.tmp)):
                t = pd.read_csv(f)
                self.assertGreater(len(t.columns), 1)
                for c in t.columns:
                    self.assertFalse(c.startswith("Unnamed") or c.startswith("#"), c)
                    if c in TEXT_COLUMNS or t.empty:  # a table without rows has no dtypes
                        continue
                    self.assertTrue(pd.api.types.is_numeric_dtype(t[c]), f"{c}: {t[c].dtype}")

    def test_metadata_in_json_sidecars(self):
        h = load(os.path.join(self.rfm_run, "hist_velocity.json"))
        self.assertIsInstance(h["n"], (int, float))
        t = pd.read_csv(os.path.join(self.rfm_run, "hist_velocity.csv"))
        self.assertEqual(len(t), h["n"])
        s = load(os.path.join(self.tap_dir, "state.json"))
        self.assertEqual(s["step"], load(os.path.join(self.tap_dir, "run.json"))["steps"])

    def test_run_json_is_typed(self):
        for d in (self.tap_dir, self.rfm_run):
            info = load(os.path.join(d, "run.json"))
            sc = info["scene"]
            self.assertEqual(info["status"], "completed")
            self.assertIsInstance(info["steps"], int)
            self.assertIsInstance(sc["integrator.dt"], float)
            self.assertIsInstance(sc["drive.taps"], int)
            self.assertIsInstance(sc["output.final_state"], bool)
            self.assertIsInstance(sc["scene.name"], str)
            self.assertIsInstance(sc["output.test_rect"], list)
        info = load(os.path.join(self.tap_dir, "run.json"))
        self.assertEqual(info["scene"]["integrator.dt"], 1e-4)
        self.assertEqual(info["scene"]["scene.name"], "tiny_tapping")
        self.assertEqual(info["scene"]["output.test_rect"], [0.01, 0.01, 0.09, 0.05])
        self.assertEqual(info["taps_done"], 22)

    def test_docs_python_snippets_run(self):
        with open(os.path.join(ROOT, "docs", "python.md")) as f:
            blocks = re.findall(r"```python\n(.*?)```", f.read(), re.S)
        self.assertGreaterEqual(len(blocks), 6)
        ns = {"run": self.tap_dir, "rfm_run": self.rfm_run, "analysis": self.analysis,
              "rfm_analysis": self.rfm_analysis}
        for i, code in enumerate(blocks):
            with self.subTest(block=i):
                exec(compile(code, f"docs/python.md block {i}", "exec"), ns)


if __name__ == "__main__":
    unittest.main()

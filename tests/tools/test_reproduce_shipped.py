"""Every report published in docs/reproduction/ with its series (series/, report.json) is
written again from them alone (python3 -m gransim.reproduce --from-series, as `gransim
reproduce … --from-series` runs it): report.md and claims.csv must come out byte for byte as shipped, so
anyone can recompute each verdict from the published folder.
Run: python3 -m unittest tests/tools/test_reproduce_shipped.py"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
PYTHON = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable


class Shipped(unittest.TestCase):
    def test_each_shipped_report_is_its_series_report(self):
        folders = sorted(os.path.dirname(p) for p in glob.glob(
            os.path.join(ROOT, "docs", "reproduction", "*", "report.json")))
        if not folders:
            self.skipTest("no report in docs/reproduction ships its series")
        for folder in folders:
            with self.subTest(report=os.path.basename(folder)):
                with open(os.path.join(folder, "report.json")) as f:
                    info = json.load(f)
                tmp = tempfile.mkdtemp(prefix="gs-shipped-")
                self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
                copy = os.path.join(tmp, "report")
                shutil.copytree(folder, copy)
                os.remove(os.path.join(copy, "report.md"))
                os.remove(os.path.join(copy, "claims.csv"))
                # the package of this source tree: its pure-Python part needs no build
                env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
                p = subprocess.run([PYTHON, "-m", "gransim.reproduce",
                                    "--study", info["study"], "--budget", info["budget"],
                                    "--from-series", copy],
                                   capture_output=True, text=True, timeout=600, env=env)
                self.assertEqual(p.returncode, 0, p.stderr[-3000:])
                for f in ("report.md", "claims.csv"):
                    with open(os.path.join(folder, f), "rb") as a, \
                            open(os.path.join(copy, f), "rb") as b:
                        self.assertEqual(b.read(), a.read(), f"{f} of {folder}")


if __name__ == "__main__":
    unittest.main()

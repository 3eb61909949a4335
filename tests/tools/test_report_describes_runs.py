"""A report describes the runs it has: the pile (grains, box, time step) comes from the runs'
scene.toml, never from the paper, and a plan that resolves nothing gives no verdict (every claim
not resolved, saying why). Fixture: the published tapping-standard analysis tables beside run
folders whose scene.toml is written here, so no run is needed.
Run: python3 -m unittest tests/tools/test_report_describes_runs.py"""
import csv
import json
import os
import shutil
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")

from gransim.reproduce import described  # noqa: E402
from gransim.reproduce import report  # noqa: E402
from gransim.reproduce import cli  # noqa: E402
from gransim.reproduce.verdicts import AGREES, DISAGREES, UNRESOLVED  # noqa: E402

PUBLISHED = os.path.join(ROOT, "docs", "reproduction", "tapping-standard")


def scene_toml(counts, width, dt):
    """the keys of a run's scene.toml that describe its pile"""
    species = "".join(f'[[species]]\nname = "{n}"\nradius = {r}\ncount = {c}\nsides = 10\n'
                      for n, r, c in zip(("big", "small"), (0.009, 0.00636), counts))
    return (f'[scene]\nname = "t"\n{species}[box]\nkind = "walls"\nwidth = {width}\n'
            f'[integrator]\nkind = "velocity_verlet"\ndt = {dt}\n'
            '[drive]\nkind = "negative_g"\nt1 = 0.01\nearly_rest = true\nquench = true\n')


class ReportDescribesItsRuns(unittest.TestCase):
    def make(self, counts, width, dt, plan):
        tmp = tempfile.mkdtemp(prefix="gs-report-runs-")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        shutil.copytree(os.path.join(PUBLISHED, "analysis"), os.path.join(tmp, "analysis"))
        os.makedirs(os.path.join(tmp, "charts"))
        with open(os.path.join(tmp, "analysis", "runs.csv"), newline="") as f:
            for r in csv.DictReader(f):
                os.makedirs(os.path.join(tmp, r["dir"]), exist_ok=True)
                with open(os.path.join(tmp, r["dir"], "scene.toml"), "w") as g:
                    g.write(scene_toml(counts, width, dt))
        with open(os.path.join(tmp, "plan.json"), "w") as f:
            json.dump(plan, f)
        here = os.getcwd()
        os.chdir(tmp)  # runs.csv names the runs relative to the report folder
        self.addCleanup(os.chdir, here)
        return tmp

    def report_md(self, tmp, budget):
        title, intro, claims, notes, facts = cli.study_claims("tapping", tmp, budget)
        report.write_report(tmp, title, intro, [], claims, notes, "tapping", facts)
        with open(os.path.join(tmp, "report.md")) as f:
            return intro, claims, f.read()

    def test_smoke_pile_and_plan(self):
        """the smoke study: 250 grains in a 0.24 m box, a plan that resolves nothing"""
        tmp = self.make((115, 135), 0.24, 1.3333333333333333e-4,
                        {"purpose": "proves the pipeline on the 250-grain teaching pile; resolves "
                         "no claim", "resolves": False})
        intro, claims, md = self.report_md(tmp, "smoke")
        self.assertIn("250 grains", intro)
        self.assertIn("115 big of radius 9 mm", intro)
        self.assertIn("0.24 m wide", intro)
        self.assertNotIn("1184 bidisperse decagons, the paper's force law", intro)
        self.assertIn("not the paper's pile", intro)
        for c in claims:
            self.assertEqual(c.verdict, UNRESOLVED, c.id)
            self.assertIn("resolves no claim", c.reason, c.id)
            self.assertTrue(c.resolve, c.id)
        self.assertIn("0 agree, 0 disagree", md)
        # the departures table: these runs' box and step, and a word that the pile is not the paper's
        self.assertIn("| 0.24 m |", md)
        self.assertNotIn("| 0.48 m |", md)
        self.assertIn("Δt = 0.0001333 s", md)
        self.assertIn("These runs tap a pile of 250 grains", md)

    def test_a_plan_that_resolves_keeps_its_verdicts(self):
        """the paper's pile under a plan that resolves claims: verdicts, and no disclaimer"""
        tmp = self.make((544, 640), 0.48, 1 / 7500,
                        {"purpose": "the paper's pile, 200–250 taps per value", "resolves": True})
        intro, claims, md = self.report_md(tmp, "standard")
        self.assertIn("1184 grains", intro)
        self.assertNotIn("not the paper's pile", intro)
        self.assertTrue(any(c.verdict in (AGREES, DISAGREES) for c in claims))
        self.assertIn("| 0.48 m |", md)
        self.assertNotIn("These runs tap a pile", md)

    def test_plan_without_the_field(self):
        """a plan.json written before the field: its purpose says it"""
        self.assertFalse(described.plan_resolves({"purpose": "x; resolves no claim"})[0])
        self.assertTrue(described.plan_resolves({"purpose": "the paper's pile"})[0])
        self.assertFalse(described.plan_resolves({"purpose": "the paper's pile",
                                                  "resolves": False})[0])

    def test_rfm_systems_from_the_runs(self):
        """the RFM report names the systems its runs simulated, not the thesis' defaults"""
        from gransim.reproduce import rfm
        tmp = tempfile.mkdtemp(prefix="gs-report-rfm-")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        with open(os.path.join(ROOT, "scenes", "rfm2d_reference.toml")) as f:
            text = f.read().replace("count = 2000", "count = 500")
        os.makedirs(os.path.join(tmp, "sweeps", "reference", "a"))
        with open(os.path.join(tmp, "sweeps", "reference", "a", "scene.toml"), "w") as f:
            f.write(text.replace("discard_time = 1.0", "discard_time = 0.1"))
        with open(os.path.join(ROOT, "scenes", "rfm1d_reference.toml")) as f:
            ring = f.read().replace("count = 1000", "count = 200")
        os.makedirs(os.path.join(tmp, "sweeps", "ring", "n"))
        with open(os.path.join(tmp, "sweeps", "ring", "n", "scene.toml"), "w") as f:
            f.write(ring)
        os.makedirs(os.path.join(tmp, "charts"))
        with open(os.path.join(tmp, "plan.json"), "w") as f:
            json.dump({"purpose": "proves the pipeline; resolves no claim", "resolves": False}, f)
        title, intro, claims, notes, facts = cli.study_claims("rfm", tmp, "smoke")
        self.assertIn("the 2D reference fluid (N = 500, L = 0.2 m, φ = 0.0884, ε = 0.6)", intro)
        self.assertNotIn("N = 2000", intro)
        self.assertNotIn("structure fluid (", intro)  # no run of it here
        for c in claims:
            self.assertEqual(c.verdict, UNRESOLVED, c.id)
            self.assertIn("resolves no claim", c.reason, c.id)
        self.assertIn("These runs discard 0.1 s.", " ".join(notes))
        report.write_report(tmp, title, intro, [], claims, notes, "rfm", facts)
        with open(os.path.join(tmp, "report.md")) as f:
            md = f.read()
        # the departures table: the ring these runs have, their step, not the plan of another budget
        self.assertIn("the largest ring of these runs' size series (N = 200)", md)
        self.assertNotIn("N = 4000 below the full budget", md)
        self.assertIn("Δt = 1e-06 s (≈ 19 steps a contact)", md)

    def test_rfm_runs_at_the_thesis_conditions_depart_from_nothing(self):
        """free paths at the thesis' L = 0.6 m and G₁ at its N = 512, each in the sweep its claim
        reads: the departures table has no row for either, and the introduction names both"""
        from gransim.reproduce import departures, rfm
        tmp = tempfile.mkdtemp(prefix="gs-report-rfm-")
        self.addCleanup(shutil.rmtree, tmp, ignore_errors=True)
        with open(os.path.join(ROOT, "scenes", "rfm2d_structure.toml")) as f:
            fluid = f.read().replace("count = 3000", "count = 27000").replace(
                "width = 0.2", "width = 0.6").replace("height = 0.2", "height = 0.6")
        with open(os.path.join(ROOT, "scenes", "rfm1d_reference.toml")) as f:
            ring = f.read().replace("count = 1000", "count = 512")
        for sweep, text in (("freepath", fluid), ("ring_n512", ring), ("ring", ring.replace(
                "count = 512", "count = 4000"))):
            os.makedirs(os.path.join(tmp, "sweeps", sweep, "seed=1"))
            with open(os.path.join(tmp, "sweeps", sweep, "seed=1", "scene.toml"), "w") as f:
                f.write(text)
        plan = {"sweeps": [
            {"name": "ring_n512", "conditions": {"dimension": 1, "claims": ["G1-bisection"],
                                                 "points": [{"N": 512, "eps_n": 0.1,
                                                             "reduced_length": 1.0}]}},
            {"name": "freepath", "conditions": {"dimension": 2, "claims": ["Df-freepath"],
                                                "points": [{"phi": 0.53, "eps_n": 0.1,
                                                            "eps_t": 0.1, "L": 0.6,
                                                            "N": 27000}]}},
            {"name": "ring", "conditions": {"dimension": 1, "claims": ["xi2"],
                                            "points": [{"N": 4000, "eps_n": 0.1,
                                                        "reduced_length": 1.0}]}}]}
        with open(os.path.join(tmp, "plan.json"), "w") as f:
            json.dump(plan, f)
        facts = rfm.departure_facts(tmp)
        self.assertEqual(facts["free_path_box"], [0.6])
        self.assertEqual(facts["ring_n"], [512])  # the ring G₁ reads, not the size series
        names = [r[0] for r in departures.rows("rfm", facts)]
        self.assertNotIn("box of the free-path dimension", names)
        self.assertNotIn("ring of the gap distribution G₁", names)
        self.assertIn("time step", names)
        # a free-path box other than the thesis' is still a departure, with the runs' value
        facts["free_path_box"] = [0.2]
        row = [r for r in departures.rows("rfm", facts) if r[0] == "box of the free-path dimension"]
        self.assertIn("L = 0.2 m", row[0][2])
        intro = cli.study_claims("rfm", tmp, "standard")[1]
        self.assertIn("the free-path fluid (N = 27000, L = 0.6 m", intro)
        self.assertIn("the 1D ring of G₁ and T(t) (N = 512", intro)

    def test_no_scene_no_pile(self):
        """without the runs' scene.toml the report says so, and names no pile"""
        self.assertIsNone(described.pile(described.scenes(["/nonexistent"])))


if __name__ == "__main__":
    unittest.main()

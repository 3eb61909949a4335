"""`gransim reproduce STUDY --budget smoke` end to end: the command runs, the report has a row for
every claim with a verdict, report.html opens in headless Chromium without errors and shows
a page that is not blank, and the published folder (tools/reproduce_publish.py) writes the same
report.md and claims.csv again from its shipped series alone (--from-series). Needs GS_BINARY
(the gransim executable); GS_STUDY picks one study.
Run: GS_BINARY=build/gransim python3 -m unittest tests/tools/test_reproduce_smoke.py"""
import csv
import fcntl
import glob
import gzip
import json
import os
import shutil
import subprocess
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

BINARY = os.environ.get("GS_BINARY", "build/gransim")
PYTHON = os.environ.get("GS_PYTHON", "/usr/bin/python3" if os.path.exists("/usr/bin/python3")
                        else "python3")
CLAIMS = {
    "tapping": ["steady-state", "neg-minimum", "neg-sigma-maximum", "rot-crossover", "rot-levels",
                "halves-mean", "halves-sigma", "normality", "reference-overlap", "q-linear",
                "two-references",
                "one-curve", "quadron-a", "protocol-fits", "lnz", "sigma-phi", "rot-sigma",
                "cross-references", "timestep", "stress", "segregation"],
    "rfm": ["T-start", "T-mean-field", "transient", "Df-Sk", "Df-freepath", "alpha-reference",
            "alpha-structure", "xi2", "xi-m", "G1-bisection", "T-ring-settle", "xi2-eps", "collapse",
            "xi-m-elastic", "v-pdf", "zeta-m",
            "g-R", "moments-phi", "alpha-phi", "crossover", "spm-alpha", "spm-pv", "cascade"],
}
VERDICTS = {"agrees", "disagrees", "not resolved"}


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        path = shutil.which(name)
        if path:
            return path
    return None


class ReproduceSmoke(unittest.TestCase):
    def run_study(self, study):
        out = tempfile.mkdtemp(prefix=f"gs-reproduce-{study}-")
        self.addCleanup(shutil.rmtree, out, ignore_errors=True)
        p = subprocess.run([BINARY, "reproduce", study, "--budget", "smoke", "--out", out, "-q",
                            "--jobs", "2"], capture_output=True, text=True, timeout=1500)
        self.assertEqual(p.returncode, 0, p.stdout[-3000:] + p.stderr[-3000:])
        self.check_pool(out, p.stderr)
        for f in ("report.md", "report.html", "claims.csv", "plan.json", "progress.json"):
            self.assertTrue(os.path.exists(os.path.join(out, f)), f)
        with open(os.path.join(out, "claims.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        ids = [r["id"] for r in rows]
        if study in CLAIMS:
            self.assertEqual(ids, CLAIMS[study])
        self.assertGreaterEqual(len(ids), 5)
        for r in rows:
            self.assertIn(r["verdict"], VERDICTS, r["id"])
            self.assertTrue(r["reason"], r["id"])
        with open(os.path.join(out, "report.md")) as f:
            md = f.read()
        for i in ids:
            self.assertIn(f"[{i}](#{i})", md)
        self.check_html(os.path.join(out, "report.html"), ids)
        self.check_from_series(study, out)
        if study == "tapping":
            # the pool and its locks are one piece of C++ for both studies: tested once
            # a second call continues the same directory: nothing to run, the report again
            p = subprocess.run([BINARY, "reproduce", study, "--budget", "smoke", "--out", out,
                                "-q"], capture_output=True, text=True, timeout=600)
            self.assertEqual(p.returncode, 0, p.stderr[-3000:])
            self.check_locks(study, out)
        self.check_partial(study, out)

    def check_from_series(self, study, out):
        """the published folder holds no run, names no path of this machine, and its series
        alone give report.md and claims.csv again, byte for byte; a changed series changes them"""
        pub = tempfile.mkdtemp(prefix=f"gs-reproduce-{study}-pub-")
        self.addCleanup(shutil.rmtree, pub, ignore_errors=True)
        tools = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")
        p = subprocess.run([PYTHON, os.path.join(tools, "reproduce_publish.py"), out, pub],
                           capture_output=True, text=True, timeout=300)
        self.assertEqual(p.returncode, 0, p.stderr[-3000:])
        self.assertFalse(os.path.exists(os.path.join(pub, "sweeps")))
        shipped = {}
        for f in ("report.md", "claims.csv"):
            with open(os.path.join(pub, f), "rb") as fh:
                shipped[f] = fh.read()
        for d, _, files in os.walk(pub):
            for f in files:
                path = os.path.join(d, f)
                with (gzip.open if f.endswith(".gz") else open)(path, "rb") as fh:
                    data = fh.read()
                self.assertNotIn(os.path.realpath(out).encode(), data, path)
        with open(os.path.join(pub, "report.json")) as f:
            inputs = json.load(f)["inputs"]
        self.assertTrue(any(i.startswith("sweeps/") for i in inputs), inputs)  # the runs' series
        os.remove(os.path.join(pub, "report.md"))
        cmd = [BINARY, "reproduce", study, "--budget", "smoke", "--out", pub, "--from-series"]
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        self.assertEqual(p.returncode, 0, p.stderr[-3000:])
        for f, want in shipped.items():
            with open(os.path.join(pub, f), "rb") as fh:
                self.assertEqual(fh.read(), want, f"{f} written again from series/ differs")
        # the verdicts read the shipped series, not a copy elsewhere: emptied, the report changes
        summary = [i for i in inputs if i.endswith(("summary.csv", "rfm_summary.json"))][0]
        with gzip.open(os.path.join(pub, "series", summary + ".gz"), "rb") as f:
            head = f.read().splitlines(keepends=True)[:1]
        with gzip.open(os.path.join(pub, "series", summary + ".gz"), "wb") as f:
            f.write(b"".join(head) if summary.endswith(".csv") else b'{"runs": []}')
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
        with open(os.path.join(pub, "claims.csv"), "rb") as fh:
            changed = p.returncode != 0 or fh.read() != shipped["claims.csv"]
        self.assertTrue(changed, "claims.csv did not change with its series emptied")
        # not a report folder: a clear refusal
        p = subprocess.run([BINARY, "reproduce", study, "--budget", "smoke", "--out",
                            os.path.join(pub, "charts"), "--from-series"],
                           capture_output=True, text=True, timeout=60)
        self.assertEqual(p.returncode, 2, p.stderr[-3000:])
        self.assertIn("report.json", p.stderr)

    def check_partial(self, study, out):
        """a report of a study whose last sweep has not begun: every claim is still listed and
        the report says what it lacks"""
        part = tempfile.mkdtemp(prefix=f"gs-reproduce-{study}-part-")
        self.addCleanup(shutil.rmtree, part, ignore_errors=True)
        shutil.copytree(out, part, dirs_exist_ok=True)
        with open(os.path.join(part, "plan.json")) as f:
            last = json.load(f)["sweeps"][-1]["name"]
        shutil.rmtree(os.path.join(part, "sweeps", last))
        p = subprocess.run([BINARY, "reproduce", study, "--budget", "smoke", "--out", part, "-q",
                            "--report-only"], capture_output=True, text=True, timeout=600)
        self.assertEqual(p.returncode, 0, p.stderr[-3000:])
        self.assertIn(f"sweep {last} has not begun", p.stderr)
        with open(os.path.join(part, "claims.csv"), newline="") as f:
            ids = [r["id"] for r in csv.DictReader(f)]
        if study in CLAIMS:
            self.assertEqual(ids, CLAIMS[study])
        with open(os.path.join(part, "report.md")) as f:
            self.assertIn("**in progress**", f.read())

    def check_pool(self, out, stderr):
        """the study's runs are one pool: the second sweep's first run starts (writes its
        scene.toml) before the first sweep's last run ends (writes its final run.json). With two
        slots and three runs in the first sweep this holds unless its third run is shorter than
        the gap between the ends of the first two, which runs of one pile never are"""
        with open(os.path.join(out, "plan.json")) as f:
            names = [s["name"] for s in json.load(f)["sweeps"]]
        if len(names) < 2:
            return
        self.assertIn("with the other sweeps' runs", stderr)
        first = glob.glob(os.path.join(out, "sweeps", names[0], "*", "run.json"))
        second = glob.glob(os.path.join(out, "sweeps", names[1], "*", "scene.toml"))
        if len(first) < 3:
            return
        self.assertLess(min(os.path.getmtime(f) for f in second),
                        max(os.path.getmtime(f) for f in first))

    def check_locks(self, study, out):
        """while another process writes the runs, --report-only reports beside it (and adds no
        sitting) but a second writer is refused; two reports at once are refused too"""
        base = [BINARY, "reproduce", study, "--budget", "smoke", "--out", out, "-q"]
        with open(os.path.join(out, "progress.json")) as f:
            before = json.load(f)
        with open(os.path.join(out, ".lock"), "a+") as held:
            fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
            p = subprocess.run(base, capture_output=True, text=True, timeout=600)
            self.assertEqual(p.returncode, 2, p.stderr[-3000:])
            self.assertIn("is writing here", p.stderr)
            p = subprocess.run(base + ["--report-only"], capture_output=True, text=True,
                               timeout=600)
            self.assertEqual(p.returncode, 0, p.stderr[-3000:])
        with open(os.path.join(out, "progress.json")) as f:
            self.assertEqual(json.load(f), before)
        with open(os.path.join(out, ".report.lock"), "a+") as held:
            fcntl.flock(held, fcntl.LOCK_EX | fcntl.LOCK_NB)
            p = subprocess.run(base + ["--report-only"], capture_output=True, text=True,
                               timeout=600)
            self.assertEqual(p.returncode, 2, p.stderr[-3000:])
            self.assertIn("is writing here; reproduce --report-only refused", p.stderr)

    def check_html(self, path, ids):
        exe = chromium()
        if exe is None:
            self.skipTest("chromium is not installed (tools/test.sh installs it)")
        shot = path + ".png"
        args = [exe, "--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                "--enable-logging=stderr", "--v=0", "--window-size=1200,1600"]
        p = subprocess.run(args + [f"--screenshot={shot}", "file://" + path],
                           capture_output=True, text=True, timeout=180)
        self.assertEqual(p.returncode, 0, p.stderr[-2000:])
        for bad in ("Uncaught", "ERR_FILE_NOT_FOUND", "Failed to load resource"):
            self.assertNotIn(bad, p.stderr)
        img = mpimg.imread(shot)
        self.assertGreater(img.shape[0], 500)
        # not blank: many distinct shades, a sizeable share of non-white pixels
        gray = img[..., :3].mean(axis=2)
        self.assertGreater((gray < 0.9).mean(), 0.02)
        self.assertGreater(len(set((gray * 255).astype(int).ravel().tolist())), 20)
        dom = subprocess.run(args + ["--dump-dom", "file://" + path], capture_output=True,
                             text=True, timeout=180)
        self.assertEqual(dom.returncode, 0, dom.stderr[-2000:])
        for i in ids:
            self.assertIn(f'id="{i}"', dom.stdout)
        self.assertIn("data:image/png;base64,", dom.stdout)

    def test_tapping(self):
        if os.environ.get("GS_STUDY", "tapping") == "tapping":
            self.run_study("tapping")

    def test_rfm(self):
        if os.environ.get("GS_STUDY", "rfm") == "rfm":
            self.run_study("rfm")


if __name__ == "__main__":
    unittest.main()

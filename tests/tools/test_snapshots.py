"""Snapshots and trajectories read by the tools researchers use: ASE reads every extended XYZ
file (count, positions, cell), VTK's own XML reader every .vtp (cells, points, cell data) and the
.pvd lists them with their times, pandas reads each contact CSV as is with one row per contact,
and on the pile at rest at a tap's measurement the forces on the walls carry its weight.
Run by ctest with GS_BINARY set to the gransim binary."""
import glob
import json
import math
import os
import shutil
import subprocess
import tempfile
import unittest
import xml.etree.ElementTree as ET
import sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tiny_scenes import tiny_tapping  # noqa: E402

import ase.io
import numpy as np
import pandas as pd
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", ".."))
BINARY = os.environ.get("GS_BINARY", os.path.join(SOURCE, "build", "gransim"))

# 4 taps of T = 1 s; snapshots every 0.4 s and at each tap's measurement, a trajectory frame
# every 0.5 s
TAPPING = tiny_tapping(1.0, 4, """[output.snapshots]
every_time = 0.4
at_taps = true
[render]
trajectory_every = 5000
""")


def run(args, cwd):
    env = dict(os.environ, OMP_NUM_THREADS="1")
    p = subprocess.run([BINARY] + args, cwd=cwd, env=env, capture_output=True, text=True,
                       timeout=300)
    if p.returncode != 0:
        raise AssertionError("gransim %s failed (%d):\n%s%s" % (args, p.returncode, p.stdout,
                                                                p.stderr))


def load_json(path):
    with open(path) as f:
        return json.load(f)


def read_vtp(path):
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def outlines(pd_):
    """each cell's vertices as an (n, 3) array"""
    pts = vtk_to_numpy(pd_.GetPoints().GetData())
    polys = pd_.GetPolys()
    offsets = vtk_to_numpy(polys.GetOffsetsArray())
    conn = vtk_to_numpy(polys.GetConnectivityArray())
    return [pts[conn[offsets[c]:offsets[c + 1]]] for c in range(pd_.GetNumberOfCells())]


def polygon_area(v):
    x, y = v[:, 0], v[:, 1]
    return 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


class Snapshots(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="gs_snapshots_py_")
        with open(os.path.join(cls.tmp, "tiny.toml"), "w") as f:
            f.write(TAPPING)
        run(["run", "tiny.toml", "--out", "tap", "--quiet"], cls.tmp)
        # 50 disks in a periodic box (Model S): disks as polygons of many vertices, wrapped
        run(["run", os.path.join(SOURCE, "scenes", "rfm2d_reference.toml"), "--out", "disks",
             "--quiet", "--set", "species[0].count=50", "--set", "scene.duration=0.002",
             "--set", "rfm.enabled=false", "--set", "output.snapshots.every_time=0.001",
             "--set", "render.trajectory_every=1000"], cls.tmp)
        # the same pile at rest: one tap and 1.5 s to come to rest, at Δt = 2.5e-5 s (28 steps
        # per contact: the integrator leaves no jitter)
        rest = TAPPING.replace("period = 1.0", "period = 1.5").replace("taps = 4", "taps = 1")
        rest = rest.replace("dt = 1e-4", "dt = 2.5e-5").replace("every_time = 0.4\n", "")
        with open(os.path.join(cls.tmp, "rest.toml"), "w") as f:
            f.write(rest.replace("trajectory_every = 5000", "trajectory_every = 0"))
        run(["run", "rest.toml", "--out", "rest", "--quiet"], cls.tmp)
        cls.runs = [os.path.join(cls.tmp, d) for d in ("tap", "disks", "rest")]

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def snap(self, run_dir, name):
        return os.path.join(run_dir, "snapshots", name)

    def index(self, run_dir):
        return pd.read_csv(self.snap(run_dir, "index.csv"))

    def test_the_schedule(self):
        tap = os.path.join(self.tmp, "tap")
        idx = self.index(tap)
        # every taps.csv row (tap 0 … 4) has its snapshot, at the same time, with its tap
        taps = pd.read_csv(os.path.join(tap, "taps.csv"))
        at = idx[idx["at_tap"] == 1]
        self.assertEqual(list(at.tap), list(taps.tap))
        np.testing.assert_allclose(at.t, taps.t, rtol=0, atol=1e-12)
        # and t = 0, 0.4, …, 4.4 (the run ends at 4.5 s), within half a step
        timed = idx[idx["at_time"] == 1]
        np.testing.assert_allclose(timed.t, 0.4 * np.arange(12), rtol=0, atol=0.5e-4)
        self.assertEqual(list(idx.snapshot), list(range(len(idx))))

    def test_ase_reads_every_xyz_with_count_positions_and_cell(self):
        for run_dir in self.runs:
            scene = load_json(os.path.join(run_dir, "run.json"))["scene"]
            lx, ly = float(scene["box.width"]), float(scene["box.height"])
            periodic = scene["box.kind"] == "periodic"  # run.json holds typed values
            idx = self.index(run_dir)
            files = sorted(glob.glob(self.snap(run_dir, "snap_*.xyz")))
            self.assertEqual(len(files), len(idx))
            for k, path in enumerate(files):
                frames = ase.io.read(path, ":")
                self.assertEqual(len(frames), 1, path)
                a = frames[0]
                np.testing.assert_allclose(a.cell.lengths(), [lx, ly, 1.0])
                self.assertEqual(list(a.pbc), [periodic, periodic, False])
                self.assertAlmostEqual(a.info["Time"], idx.t[k], places=9)
                self.assertEqual(a.info["Step"], idx.step[k])
                # element-like symbols by species index, the names beside them
                sym = a.get_chemical_symbols()
                for s, i, n in zip(sym, a.arrays["species_index"], a.arrays["name"]):
                    self.assertEqual(s, ["H", "He"][i])
                    self.assertEqual(n, ["big", "small"][i] if not periodic else "bead")
                self.assertEqual(list(a.arrays["id"]), list(range(len(a))))
            # the last snapshot is the final state: positions, velocities and ω
            state = pd.read_csv(os.path.join(run_dir, "state.csv"), comment="#")
            last = ase.io.read(files[-1])
            self.assertEqual(last.info["Step"], load_json(os.path.join(run_dir, "run.json"))["steps"])
            np.testing.assert_allclose(last.positions[:, 0], state.x, rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(last.positions[:, 1], state.y, rtol=1e-9, atol=1e-12)
            np.testing.assert_allclose(last.positions[:, 2], 0.0)
            np.testing.assert_allclose(last.arrays["velo"][:, 1], state.vy, rtol=1e-7, atol=1e-15)
            # ω in the z component: OVITO's Angular Velocity
            np.testing.assert_allclose(last.arrays["omega"][:, 2], state.omega, rtol=1e-9,
                                       atol=1e-15)
            np.testing.assert_allclose(last.arrays["omega"][:, :2], 0.0)
            # the trajectory: one frame at step 0 and every trajectory_every steps
            steps = load_json(os.path.join(run_dir, "run.json"))["steps"]
            every = int(scene["render.trajectory_every"])
            if every == 0:
                continue
            traj = ase.io.read(os.path.join(run_dir, "trajectory.xyz"), ":")
            self.assertEqual(len(traj), steps // every + 1)
            self.assertEqual([a.info["Step"] for a in traj], [every * k for k in range(len(traj))])
            np.testing.assert_allclose(traj[-1].positions, last.positions, rtol=1e-9, atol=1e-12)

    def test_vtk_reads_every_vtp_and_the_pvd_lists_them(self):
        for run_dir in self.runs:
            idx = self.index(run_dir)
            files = sorted(glob.glob(self.snap(run_dir, "snap_*.vtp")))
            self.assertEqual(len(files), len(idx))
            for k, path in enumerate(files):
                pd_ = read_vtp(path)
                atoms = ase.io.read(path[:-3] + "xyz")
                n = len(atoms)
                self.assertEqual(pd_.GetNumberOfCells(), n, path)
                sides = vtk_to_numpy(pd_.GetCellData().GetArray("sides"))
                # decagons: 10 vertices each; disks: 32-gons
                self.assertEqual(pd_.GetNumberOfPoints(), int(np.where(sides > 0, sides, 32).sum()))
                for name in ("id", "species", "radius", "sides", "theta", "velocity", "omega",
                             "speed", "contacts"):
                    arr = pd_.GetCellData().GetArray(name)
                    self.assertIsNotNone(arr, name)
                    self.assertEqual(arr.GetNumberOfTuples(), n, name)
                self.assertAlmostEqual(pd_.GetFieldData().GetArray("TimeValue").GetValue(0),
                                       idx.t[k], places=9)
                # each outline is centred on its grain (wrapped into a periodic box) with
                # its vertices at the circumradius
                radius = vtk_to_numpy(pd_.GetCellData().GetArray("radius"))
                cell = atoms.cell.lengths()
                for c, v in enumerate(outlines(pd_)):
                    centre = v.mean(axis=0)[:2]
                    d = (centre - atoms.positions[c, :2]) / cell[:2]
                    if atoms.pbc[0]:
                        d -= np.round(d)
                    np.testing.assert_allclose(d, 0.0, atol=1e-9)
                    np.testing.assert_allclose(np.hypot(*(v[:, :2] - centre).T), radius[c], atol=1e-10,
                                               rtol=1e-8)
                np.testing.assert_array_equal(vtk_to_numpy(pd_.GetCellData().GetArray("contacts")),
                                              atoms.arrays["contacts"])
            # the collection: every .vtp once, in order, with its time
            root = ET.parse(self.snap(run_dir, "snapshots.pvd")).getroot()
            self.assertEqual(root.get("type"), "Collection")
            sets = root.find("Collection").findall("DataSet")
            self.assertEqual([s.get("file") for s in sets], [os.path.basename(f) for f in files])
            np.testing.assert_allclose([float(s.get("timestep")) for s in sets], idx.t,
                                       rtol=1e-9)

    def test_contact_csv_reads_as_is_one_row_per_contact(self):
        for run_dir in self.runs:
            series = pd.read_csv(os.path.join(run_dir, "series.csv"))
            idx = self.index(run_dir)
            for k in range(len(idx)):
                c = pd.read_csv(self.snap(run_dir, "contacts_%06d.csv" % k))
                self.assertEqual(list(c.columns), ["i", "j", "wall", "x", "y", "nx", "ny", "fn",
                                                   "ft", "fx", "fy", "overlap", "sliding"])
                for col in ("i", "j", "wall", "sliding"):
                    self.assertTrue(len(c) == 0 or pd.api.types.is_integer_dtype(c[col]), col)
                # the run's own count of contacts at that step (series.csv), and per grain
                row = series[series.step == idx.step[k]]
                if len(row):
                    self.assertEqual(len(c), int(row.contacts.iloc[0]))
                z = ase.io.read(self.snap(run_dir, "snap_%06d.xyz" % k)).arrays["contacts"]
                pairs = c[c.wall < 0]
                self.assertEqual(z.sum(), 2 * len(pairs) + (len(c) - len(pairs)))
                self.assertTrue(((c.wall < 0) == (c.j >= 0)).all())
                if len(c):
                    np.testing.assert_allclose(np.hypot(c.nx, c.ny), 1.0, rtol=1e-12)

    def test_resting_pile_walls_carry_its_weight(self):
        rest = os.path.join(self.tmp, "rest")
        info = load_json(os.path.join(rest, "run.json"))
        idx = self.index(rest)
        last = idx[idx["at_tap"] == 1].snapshot.iloc[-1]
        c = pd.read_csv(self.snap(rest, "contacts_%06d.csv" % last))
        a = ase.io.read(self.snap(rest, "snap_%06d.xyz" % last))
        # the grains' mass: their outlines' area × the areal density (1 kg/m², the default)
        mass = sum(polygon_area(v) for v in outlines(read_vtp(self.snap(
            rest, "snap_%06d.vtp" % last))))
        g = 9.81
        walls = c[c.wall >= 0]
        # Σ_walls F = M g − Σ m a: grain-grain forces cancel in pairs. At rest the pile can only
        # vibrate on its contacts, no faster than ω = π/t_c (t_c the shortest contact time),
        # with a momentum of at most M v_max, so |Σ m a| ≤ M v_max π/t_c and
        # |Σ_walls F_y/(M g) − 1| ≤ π v_max/(t_c g)
        v_max = a.arrays["speed"].max()
        tol = math.pi * v_max / info["contact_time_s"] / g
        fy, fx = walls.fy.sum(), walls.fx.sum()
        self.assertLess(abs(fy / (-mass * g) - 1.0), tol, (fy, -mass * g, v_max, tol))
        self.assertLess(abs(fx) / (mass * g), tol, (fx, mass * g, v_max, tol))
        # the bound means something: this pile is at rest (a wall's rows left out, a sign or
        # a lost tangential component would each cost far more than 0.5 %)
        self.assertLess(tol, 0.005)

if __name__ == "__main__":
    unittest.main()

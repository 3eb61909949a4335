"""The binary outputs read by the tools researchers use: the H5MD trajectory opened with h5py
(positions, time, box against the extended XYZ of the same run and its final state) and with
MDAnalysis' H5MDReader; a killed and resumed run's H5MD file holds every frame once, as the
uninterrupted run's; compressed binary .vtp read by VTK gives the ASCII file's numbers; the
bytes per grain per frame of each format stay within the margin of the figures in
docs/rendering.md. Run by ctest with GS_BINARY set to the gransim binary."""
import glob
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tiny_scenes import tiny_tapping  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, "..", ".."))
BINARY = os.environ.get("GS_BINARY", os.path.join(SOURCE, "build", "gransim"))
ENV = dict(os.environ, OMP_NUM_THREADS="1")

# the 250 decagons of the small tapping scene settling for 0.5 s and tapped once (30000 steps
# of 5e-5 s): a trajectory frame every 1000 steps and a snapshot every 0.1 s (the scene the size
# figures of docs/rendering.md are measured on, there over a longer run)
N = 250
FRAMES = 31
TAPPING = [os.path.join(SOURCE, "scenes", "tap_small_negative_g.toml"), "--quiet",
           "--set", "preparation.settle_time=0.5", "--set", "drive.taps=1",
           "--set", "drive.period=1.0",
           "--set", "render.trajectory_every=1000",
           "--set", 'render.trajectory_formats=["xyz", "h5md"]',
           "--set", "output.snapshots.every_time=0.1",
           "--set", "output.snapshots.contacts=false"]


def run(args, cwd):
    p = subprocess.run([BINARY] + args, cwd=cwd, env=ENV, capture_output=True, text=True,
                       timeout=300)
    if p.returncode != 0:
        raise AssertionError("gransim %s failed (%d):\n%s%s" % (args, p.returncode, p.stdout,
                                                                p.stderr))


def xyz_frames(path):
    """(time, step, lattice, positions N×2) of each frame of an extended XYZ file"""
    frames = []
    with open(path) as f:
        while True:
            head = f.readline()
            if not head.strip():
                return frames
            n = int(head)
            comment = f.readline()
            lat = [float(v) for v in re.search(r'Lattice="([^"]*)"', comment).group(1).split()]
            t = float(re.search(r"Time=(\S+)", comment).group(1))
            step = int(re.search(r"Step=(\S+)", comment).group(1))
            pos = np.array([[float(v) for v in f.readline().split()[1:3]] for _ in range(n)])
            frames.append((t, step, (lat[0], lat[4]), pos))


def documented_sizes():
    """format → bytes per grain per frame, and the margin, from docs/rendering.md's table"""
    with open(os.path.join(SOURCE, "docs", "rendering.md"), encoding="utf-8") as f:
        text = f.read()
    margin = float(re.search(r"within ±(\d+) %", text).group(1)) / 100.0
    table = text[text.index("| format | file | bytes per grain per frame |"):]
    sizes = {}
    for line in table.splitlines()[2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        sizes[cells[0]] = float(cells[2])
    return sizes, margin


class H5mdAndBinaryVtp(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.mkdtemp(prefix="gs_h5md_py_")
        run(["run"] + TAPPING + ["--out", "bin"], cls.tmp)
        run(["run"] + TAPPING + ["--out", "ascii", "--set", "render.trajectory_every=0",
                                 "--set", 'output.snapshots.vtp_encoding="ascii"'], cls.tmp)
        cls.dir = os.path.join(cls.tmp, "bin")
        cls.h5 = os.path.join(cls.dir, "trajectory.h5md")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def test_h5py_reads_the_frames_of_the_xyz_and_the_final_state(self):
        frames = xyz_frames(os.path.join(self.dir, "trajectory.xyz"))
        self.assertEqual(len(frames), FRAMES)  # step 0 and every 1000 steps to 30000
        with h5py.File(self.h5, "r") as f:
            self.assertEqual(list(f["h5md"].attrs["version"]), [1, 1])
            self.assertEqual(f["h5md/creator"].attrs["name"], "gransim")
            p = f["particles/all"]
            self.assertEqual(p["box"].attrs["dimension"], 3)
            self.assertEqual(list(p["box"].attrs["boundary"]), ["none"] * 3)  # walls
            pos, time_, step = p["position/value"], p["position/time"], p["position/step"]
            self.assertEqual(pos.shape, (FRAMES, N, 3))
            self.assertEqual(pos.compression, "gzip")
            self.assertNotIn("unit", pos.attrs)  # m; MDAnalysis would refuse "m"
            self.assertEqual(p["velocity/value"].attrs["unit"], "m s-1")
            for k, (t, st, lat, xy) in enumerate(frames):
                # the XYZ has 10 significant digits, the H5MD the doubles themselves
                self.assertAlmostEqual(time_[k], t, delta=1e-9 * max(t, 1e-12))
                self.assertEqual(step[k], st)
                np.testing.assert_allclose(pos[k, :, :2], xy, rtol=1e-9, atol=1e-12)
                np.testing.assert_array_equal(pos[k, :, 2], 0.0)
                np.testing.assert_allclose(np.diag(p["box/edges/value"][k]), [*lat, 1.0])
            # the last frame is the final state, exactly (state.csv has 17 digits)
            import pandas as pd
            state = pd.read_csv(os.path.join(self.dir, "state.csv"), float_precision="round_trip")
            with open(os.path.join(self.dir, "state.json")) as s:
                meta = json.load(s)
            self.assertEqual(step[-1], meta["step"])
            self.assertEqual(time_[-1], meta["t"])
            np.testing.assert_array_equal(pos[-1, :, 0], state.x)
            np.testing.assert_array_equal(p["velocity/value"][-1, :, 1], state.vy)
            np.testing.assert_array_equal(p["omega/value"][-1], state.omega)
            np.testing.assert_array_equal(p["id"][()], state.id)

    def test_mdanalysis_reads_the_frames_and_positions(self):
        from MDAnalysis.coordinates.H5MD import H5MDReader

        # lengths are in m, which MDAnalysis' unit table lacks: read them as they are
        r = H5MDReader(self.h5, convert_units=False)
        self.assertEqual(r.n_frames, FRAMES)
        self.assertEqual(r.n_atoms, N)
        with h5py.File(self.h5, "r") as f:
            pos = f["particles/all/position/value"][()]
            t = f["particles/all/position/time"][()]
            box = np.diag(f["particles/all/box/edges/value"][0])
        for ts in r:
            k = ts.frame
            # MDAnalysis keeps positions in float32
            np.testing.assert_allclose(ts.positions, pos[k], rtol=1e-6, atol=1e-9)
            self.assertAlmostEqual(ts.time, t[k])
            self.assertEqual(ts.data["step"], 1000 * k)
            np.testing.assert_allclose(ts.dimensions, [*box, 90, 90, 90], rtol=1e-6)
        r.close()

    def test_binary_vtp_reads_as_the_ascii_one(self):
        from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
        from vtkmodules.util.numpy_support import vtk_to_numpy

        def read(path):
            r = vtkXMLPolyDataReader()
            r.SetFileName(path)
            r.Update()
            return r.GetOutput()

        files = sorted(glob.glob(os.path.join(self.dir, "snapshots", "snap_*.vtp")))
        self.assertEqual(len(files), 16)  # t = 0, 0.1, … 1.5 s
        for path in files:
            with open(path, "rb") as f:
                self.assertIn(b'compressor="vtkZLibDataCompressor"', f.read(400))
            other = path.replace(os.sep + "bin" + os.sep, os.sep + "ascii" + os.sep)
            with open(other, "rb") as f:
                self.assertNotIn(b"compressor", f.read(400))
            b, a = read(path), read(other)
            self.assertEqual(b.GetNumberOfCells(), N)
            self.assertEqual(b.GetNumberOfPoints(), a.GetNumberOfPoints())
            np.testing.assert_allclose(vtk_to_numpy(b.GetPoints().GetData()),
                                       vtk_to_numpy(a.GetPoints().GetData()), rtol=1e-9,
                                       atol=1e-15)
            for poly in (b.GetPolys(), a.GetPolys()):
                self.assertEqual(vtk_to_numpy(poly.GetOffsetsArray())[-1], 10 * N)  # decagons
            np.testing.assert_array_equal(vtk_to_numpy(b.GetPolys().GetConnectivityArray()),
                                          vtk_to_numpy(a.GetPolys().GetConnectivityArray()))
            for name in ("id", "species", "radius", "sides", "theta", "velocity", "omega",
                         "speed", "contacts"):
                np.testing.assert_allclose(vtk_to_numpy(b.GetCellData().GetArray(name)),
                                           vtk_to_numpy(a.GetCellData().GetArray(name)),
                                           rtol=1e-9, atol=1e-15, err_msg=name)

    def test_bytes_per_grain_per_frame_are_the_documented_ones(self):
        n = N
        snaps = lambda d: sorted(glob.glob(os.path.join(self.tmp, d, "snapshots", "*.vtp")))
        per = lambda files: sum(os.path.getsize(p) for p in files) / (len(files) * n)
        measured = {
            "extended XYZ": os.path.getsize(os.path.join(self.dir, "trajectory.xyz")) / (FRAMES * n),
            "VTP, ASCII": per(snaps("ascii")),
            "VTP, binary": per(snaps("bin")),
        }
        # H5MD: the per-grain datasets' storage (the file adds a fixed ≈ 0.1 MB of its own)
        with h5py.File(self.h5, "r") as f:
            p = f["particles/all"]
            stored = sum(p[k + "/value"].id.get_storage_size()
                         for k in ("position", "velocity", "theta", "omega", "contacts"))
        measured["H5MD"] = stored / (FRAMES * n)
        sizes, margin = documented_sizes()
        self.assertEqual(set(sizes), set(measured))
        for fmt, want in sizes.items():
            self.assertLessEqual(abs(measured[fmt] - want), margin * want,
                                 f"{fmt}: measured {measured[fmt]:.1f} B, docs say {want}")


class H5mdKillResume(unittest.TestCase):
    """kill -9 after a checkpoint, with frames written after it, then `gransim resume`: the
    H5MD file holds every frame exactly once, bit for bit the uninterrupted run's"""

    def test_resumed_file_is_the_uninterrupted_one(self):
        tmp = tempfile.mkdtemp(prefix="gs_h5md_resume_")
        self.addCleanup(shutil.rmtree, tmp, True)
        with open(os.path.join(tmp, "tap.toml"), "w") as f:
            f.write(tiny_tapping(1.0, 6, """[output.snapshots]
every_time = 0.5
[render]
trajectory_every = 500
trajectory_formats = ["h5md"]
"""))
        args = ["run", "tap.toml", "--quiet", "--set", "output.checkpoint_steps=8000"]
        run(args + ["--out", "ref"], tmp)
        with h5py.File(os.path.join(tmp, "ref", "trajectory.h5md"), "r") as f:
            want = {k: f["particles/all/" + k][()] for k in
                    ("position/value", "position/step", "velocity/value", "omega/value")}
        steps = want["position/step"]
        self.assertEqual(list(steps), list(range(0, 500 * len(steps), 500)))

        # kill once a checkpoint is there and the trajectory has gone on past it
        killed = os.path.join(tmp, "killed")
        delay = 0.05
        for attempt in range(8):
            shutil.rmtree(killed, ignore_errors=True)
            p = subprocess.Popen([BINARY] + args + ["--out", "killed"], cwd=tmp, env=ENV,
                                 stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            while p.poll() is None and not glob.glob(os.path.join(killed, "checkpoint-*.gsck")):
                time.sleep(0.005)
            time.sleep(delay)
            if p.poll() is not None:  # the run ended first: kill sooner
                delay /= 2
                continue
            p.send_signal(signal.SIGKILL)
            p.wait()
            checkpoints = sorted(glob.glob(os.path.join(killed, "checkpoint-*.gsck")))
            at = int(os.path.basename(checkpoints[-1])[len("checkpoint-"):-len(".gsck")])
            with h5py.File(os.path.join(killed, "trajectory.h5md"), "r") as f:
                written = f["particles/all/position/step"][()]
            if written[-1] > at:
                break
            delay *= 2
        else:
            self.fail("no kill with frames after the checkpoint in 8 attempts")
        damaged = os.path.join(tmp, "damaged")
        shutil.copytree(killed, damaged)

        def resume(d):
            return subprocess.run([BINARY, "resume", d, "--quiet"], env=ENV, capture_output=True,
                                  text=True, timeout=300)

        r = resume(killed)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        with h5py.File(os.path.join(killed, "trajectory.h5md"), "r") as f:
            for k, v in want.items():
                np.testing.assert_array_equal(f["particles/all/" + k][()], v, err_msg=k)

        # a file a kill damaged: the resume names it and says how to go on; moved aside, a new
        # file starts at the checkpoint
        h5 = os.path.join(damaged, "trajectory.h5md")
        with open(h5, "r+b") as f:
            f.write(b"\0" * 64)
        r = resume(damaged)
        self.assertNotEqual(r.returncode, 0)
        self.assertIn("trajectory.h5md", r.stderr)
        self.assertIn("move it aside", r.stderr)
        os.rename(h5, h5 + ".damaged")
        r = resume(damaged)
        self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
        self.assertIn("a new one starts at the checkpoint", r.stderr)
        with h5py.File(h5, "r") as f:
            self.assertEqual(list(f["particles/all/position/step"][()]),
                             [s for s in steps if s > at])
            np.testing.assert_array_equal(f["particles/all/position/value"][()],
                                          want["position/value"][steps > at])


if __name__ == "__main__":
    unittest.main()

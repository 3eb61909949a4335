"""`pip install .` into a virtual environment, offline: a venv made with --system-site-packages
(Debian's setuptools, numpy and pandas), `pip install --no-build-isolation --no-index` of the
source tree; the module imports from the venv and steps a scene, and its metadata declares numpy
and pandas.

usage: test_pip_install.py BUILD_DIR [unittest args]
(BUILD_DIR: the configured CMake build, whose options the pip build repeats so that ccache
serves the compiled objects, and under which the pip build keeps its tree between runs)
"""
import os
import re
import subprocess
import sys
import tempfile
import unittest

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = None


def cache_option(name):
    """a BOOL option of the CMake build, e.g. GS_WERROR, or None"""
    path = os.path.join(BUILD, "CMakeCache.txt")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        m = re.search(r"^%s:BOOL=(\w+)$" % name, f.read(), re.M)
    return m.group(1) if m else None


class PipInstall(unittest.TestCase):
    def test_venv_install_imports_and_runs(self):
        with tempfile.TemporaryDirectory(prefix="gs-venv-") as tmp:
            venv = os.path.join(tmp, "venv")
            subprocess.run(["/usr/bin/python3", "-m", "venv", "--system-site-packages", venv],
                           check=True)
            py = os.path.join(venv, "bin", "python")
            env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME")}
            # the same compile options as the main build (ccache hits), the module target only
            opts = ["-D%s=%s" % (k, cache_option(k)) for k in
                    ("GS_WERROR", "GS_WITH_GL", "GS_WITH_FFMPEG", "GS_WITH_MPI")
                    if cache_option(k)]
            env.update(GS_PIP_BUILD_DIR=os.path.join(BUILD, "pip-test"),
                       GS_CMAKE_ARGS=" ".join(opts), GS_JOBS=env.get("GS_JOBS", "2"),
                       PIP_DISABLE_PIP_VERSION_CHECK="1")
            res = subprocess.run([py, "-m", "pip", "install", "--no-build-isolation", "--no-index",
                                  SOURCE], env=env, capture_output=True, text=True)
            self.assertEqual(res.returncode, 0, res.stdout[-4000:] + res.stderr[-4000:])

            # imported from the venv, not from the build tree, and it runs a scene
            scene = os.path.join(SOURCE, "scenes", "collision_disks.toml")
            code = ("import gransim, sys; s = gransim.Simulation(sys.argv[1]); s.step(10); "
                    "print(gransim.__file__); print(s.step_count); print(gransim.__version__)")
            res = subprocess.run([py, "-c", code, scene], env=env, cwd=tmp, capture_output=True,
                                 text=True)
            self.assertEqual(res.returncode, 0, res.stderr)
            where, steps, version = res.stdout.split()
            self.assertTrue(where.startswith(os.path.join(venv, "lib")), where)
            self.assertEqual(steps, "10")
            with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
                self.assertIn("project(gransim VERSION %s" % version, f.read())
            # the subpackages the command line runs (charts, the reproduction's report) came along
            code = ("import gransim.charts.tapping, gransim.reproduce.cli as c, sys; "
                    "print(c.__file__); print(c.study_claims.__name__)")
            res = subprocess.run([py, "-c", code], env=env, cwd=tmp, capture_output=True,
                                 text=True)
            self.assertEqual(res.returncode, 0, res.stderr)
            self.assertTrue(res.stdout.startswith(os.path.join(venv, "lib")), res.stdout)

            # the metadata declares what read_run and the arrays need
            code = ("import importlib.metadata as m; "
                    "print(' '.join(sorted(r.split()[0] for r in m.requires('gransim'))))")
            res = subprocess.run([py, "-c", code], env=env, cwd=tmp, capture_output=True,
                                 text=True, check=True)
            self.assertIn("numpy", res.stdout.split())
            self.assertIn("pandas", res.stdout.split())

            # the source tree is left as it was: no egg-info or build folder beside the sources
            self.assertFalse(os.path.exists(os.path.join(SOURCE, "gransim.egg-info")))
            self.assertFalse(os.path.exists(os.path.join(SOURCE, "python", "gransim.egg-info")))


if __name__ == "__main__":
    BUILD = os.path.abspath(sys.argv.pop(1))
    unittest.main()

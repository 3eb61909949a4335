# the type stubs (python/gransim/_gransim.pyi) are those of the module built: every public name
# of the compiled module with its signature, as tools/python_stubs.py writes them
import os
import subprocess
import sys

import pytest

import conftest


def test_stubs_match_the_module(gransim):
    if not gransim.have_movie:
        pytest.skip("the stubs are written from a build with FFmpeg (MovieEncoder, probe_movie)")
    stub = os.path.join(conftest.SOURCE_DIR, "python", "gransim", "_gransim.pyi")
    res = subprocess.run([sys.executable, os.path.join(conftest.SOURCE_DIR, "tools",
                                                       "python_stubs.py"), "--check", stub],
                         capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr
    # and the stub is valid Python naming every public function and class of the module
    import ast

    with open(stub, encoding="utf-8") as f:
        tree = ast.parse(f.read())
    named = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    public = {n for n in dir(gransim._gransim) if not n.startswith("_")
              and callable(getattr(gransim._gransim, n))}
    assert public <= named, public - named
    assert os.path.exists(os.path.join(os.path.dirname(stub), "py.typed"))


def test_api_reference_names_everything(gransim):
    # docs/python-api.md (tools/python_api_doc.py) has a heading for every export of the
    # package and every public member of its classes
    with open(os.path.join(conftest.SOURCE_DIR, "docs", "python-api.md"), encoding="utf-8") as f:
        headings = {line.split("`")[1].split("(")[0] for line in f if line.startswith("#")
                    and "`" in line}
    missing = {n for n in gransim.__all__ if n not in headings}
    for cls in (gransim.Simulation, gransim.Scene, gransim.Renderer, gransim.TrajectoryWriter,
                gransim.H5mdTrajectoryWriter, gransim.H5mdTrajectory):
        missing |= {f"{cls.__name__}.{n}" for n in dir(cls) if not n.startswith("_")
                    and f"{cls.__name__}.{n}" not in headings}
    assert not missing, f"not in docs/python-api.md (run tools/python_api_doc.py): {missing}"

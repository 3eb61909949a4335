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

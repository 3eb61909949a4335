# the teaching example runs and writes its pictures; `cmake --install` puts a module that
# imports from the prefix (Debian's dist-packages layout)
import os
import struct
import subprocess
import sys

import pytest

import conftest


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">II", head[16:24])


def test_tap_five_times_example(tmp_path):
    script = os.path.join(conftest.SOURCE_DIR, "docs", "examples", "tap_five_times.py")
    res = subprocess.run([sys.executable, script, "--out", str(tmp_path), "--grains", "30"],
                         capture_output=True, text=True, check=True,
                         env={**os.environ, "OMP_NUM_THREADS": "1", "MPLBACKEND": "Agg"})
    lines = [s for s in res.stdout.splitlines() if s.startswith("tap ")]
    assert len(lines) == 6 and lines[-1].startswith("tap 5:")
    w, h = png_size(tmp_path / "phi_per_tap.png")
    assert w > 300 and h > 200
    import gransim
    pile = gransim.read_png(str(tmp_path / "pile.png"), channels=3)
    assert pile.shape[1] == 480
    # both species' colours (coolwarm ends: blue and red) are in the picture
    r, g, b = (pile[:, :, k].astype(int) for k in range(3))
    assert ((b - r) > 80).sum() > 500 and ((r - b) > 80).sum() > 500


def test_install_into_a_prefix(tmp_path):
    build = os.environ.get("GS_BUILD_DIR")
    if not build:
        pytest.skip("GS_BUILD_DIR is not set")
    prefix = tmp_path / "prefix"
    subprocess.run(["cmake", "--install", build, "--prefix", str(prefix)], check=True,
                   capture_output=True)
    site = prefix / "lib" / "python3" / "dist-packages"
    assert (site / "gransim" / "__init__.py").exists()
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env.update(PYTHONPATH=str(site), OMP_NUM_THREADS="1")
    code = ("import gransim, sys; print(gransim.__file__); "
            "s = gransim.Simulation(sys.argv[1]); s.step(10); print(s.step_count)")
    scene = os.path.join(conftest.SOURCE_DIR, "scenes", "collision_disks.toml")
    res = subprocess.run([sys.executable, "-c", code, scene], capture_output=True, text=True,
                         check=True, env=env, cwd=str(tmp_path))
    where, steps = res.stdout.split()
    assert where.startswith(str(site))
    assert steps == "10"

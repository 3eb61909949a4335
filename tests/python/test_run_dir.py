# gransim.read_run: a run directory written by the binary as DataFrames and run.json; both CSV
# forms (a '#' preamble before the header, and plain CSV)
import os
import subprocess

import pytest

import conftest


def test_read_run_of_a_real_run(gransim, binary, tmp_path):
    doc = conftest.tiny_tapping()
    doc["drive"]["taps"] = 2
    scene = tmp_path / "tiny.toml"
    scene.write_text(gransim.scene_toml(doc))
    out = tmp_path / "run"
    subprocess.run([binary, "run", str(scene), "--out", str(out), "--quiet"], check=True,
                   env={**os.environ, "OMP_NUM_THREADS": "1"})
    run = gransim.read_run(out)
    assert run["run.json"]["status"] == "completed"
    taps = run["taps"]
    assert list(taps["tap"]) == [0, 1, 2]
    assert taps["phi"].between(0.5, 0.95).all()
    assert "kinetic_energy" in run["series"].columns
    assert len(run["series"]) > 3
    # the same numbers as the module's own measurement of the same scene
    sim = gransim.Simulation(doc)
    assert sim.run_to_tap(2)["phi"] == pytest.approx(taps["phi"].iloc[2], abs=1e-6)


def test_read_csv_both_forms(gransim, tmp_path):
    (tmp_path / "a.csv").write_text("# gransim taps\n# discard_taps=10\ntap,phi\n1,0.8\n2,0.81\n")
    (tmp_path / "b.csv").write_text("tap,phi\n1,0.8\n2,0.81\n")
    (tmp_path / "run.json").write_text('{"status": "completed", "particles": 3}')
    run = gransim.read_run(tmp_path)
    for k in ("a", "b"):
        assert list(run[k].columns) == ["tap", "phi"]
        assert list(run[k]["phi"]) == [0.8, 0.81]
    assert run["a"].attrs["meta"] == {"discard_taps": "10"}
    assert run["run.json"]["particles"] == 3


def test_read_run_missing(gransim, tmp_path):
    with pytest.raises(FileNotFoundError):
        gransim.read_run(tmp_path / "nope")

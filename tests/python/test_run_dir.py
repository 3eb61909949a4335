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


def test_read_run_reads_a_file_when_it_is_used(gransim, tmp_path):
    # a snapshot folder of many contact files: nothing is read until asked for, so a broken
    # file among them does not stop the others
    (tmp_path / "taps.csv").write_text("tap,phi\n1,0.8\n")
    snaps = tmp_path / "snapshots"
    snaps.mkdir()
    for k in range(50):
        (snaps / f"contacts_{k:06d}.csv").write_text("i,j,fn\n0,1,0.5\n")
    (snaps / "broken.json").write_text("{not json")
    run = gransim.read_run(tmp_path)
    assert len(run) == 52 and "snapshots/contacts_000049" in run
    assert run.loaded() == []
    assert list(run["taps"]["phi"]) == [0.8]
    assert run["snapshots/contacts_000007"]["fn"].iloc[0] == 0.5
    assert sorted(run.loaded()) == ["snapshots/contacts_000007", "taps"]
    assert run["taps"] is run["taps"]  # read once, kept
    with pytest.raises(ValueError):
        run["snapshots/broken.json"]
    with pytest.raises(KeyError):
        run["nope"]

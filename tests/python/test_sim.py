# the Python module's scenes and simulation: free fall against the exact answer, NumPy views
# that follow the state, contacts that carry the pile's weight, taps, and errors as InputError
import gc
import os
import subprocess
import tomllib

import numpy as np
import pytest

import conftest


def test_free_fall_matches_exact(gransim):
    sim = gransim.Simulation(conftest.one_disk(y0=0.8, dt=1e-5))
    n = 10000
    sim.step(n)
    t = n * 1e-5
    assert sim.step_count == n
    assert sim.t == pytest.approx(t, rel=1e-12)
    # velocity Verlet is exact for a constant force: only round-off remains
    assert sim.y[0] == pytest.approx(0.8 - 0.5 * 9.81 * t * t, abs=1e-12)
    assert sim.vy[0] == pytest.approx(-9.81 * t, abs=1e-12)
    assert sim.x[0] == 0.5 and sim.vx[0] == 0.0


def test_run_is_steps(gransim):
    a = gransim.Simulation(conftest.one_disk())
    b = gransim.Simulation(conftest.one_disk())
    a.run(0.005)
    b.step(500)
    assert a.step_count == 500
    assert a.y[0] == b.y[0] and a.vy[0] == b.vy[0]


def test_arrays_are_views(gransim):
    sim = gransim.Simulation(conftest.one_disk())
    y, vy = sim.y, sim.vy
    before = y.copy()
    sim.step(10)
    # the same array objects now show the new state: no copy was taken
    assert y[0] < before[0] and vy[0] < 0
    assert np.shares_memory(y, sim.y)
    assert not y.flags.writeable
    with pytest.raises(ValueError):
        y[0] = 1.0
    # the view keeps the simulation alive
    value = float(sim.y[0])
    del sim
    gc.collect()
    assert y[0] == value


def test_per_particle_arrays(gransim):
    sim = gransim.Simulation(conftest.disk_pile(n_big=3, n_small=5))
    assert len(sim) == 8
    assert sim.species_names == ["big", "small"]
    assert sorted(sim.species) == [0] * 3 + [1] * 5
    assert np.array_equal(sim.radius, np.where(sim.species == 0, 0.006, 0.004))
    assert sim.positions.shape == (8, 2) and np.array_equal(sim.positions[:, 1], sim.y)
    assert sim.velocities.shape == (8, 2)
    assert sim.theta.shape == (8,) and sim.omega.shape == (8,)
    assert sim.sort_every == 0


def test_contacts_carry_the_weight(gransim):
    sim = gransim.Simulation(conftest.disk_pile())
    sim.run(0.3)
    c = sim.contacts()
    n = len(c["i"])
    assert n > 20
    for k in ("j", "wall", "fn", "ft", "overlap"):
        assert c[k].shape == (n,)
    assert c["point"].shape == (n, 2) and c["normal"].shape == (n, 2)
    assert np.allclose(np.hypot(c["normal"][:, 0], c["normal"][:, 1]), 1.0)
    assert ((c["j"] >= 0) != (c["wall"] >= 0)).all()
    assert (c["i"] < len(sim)).all() and (c["j"] < len(sim)).all()
    # the pile at rest: the forces on the walls add up to its weight
    w = c["wall"] >= 0
    nrm = c["normal"][w]
    tangent = np.stack([-nrm[:, 1], nrm[:, 0]], axis=1)
    force = (c["fn"][w][:, None] * nrm + c["ft"][w][:, None] * tangent).sum(axis=0)
    weight = sim.mass.sum() * 9.81
    assert force[1] == pytest.approx(-weight, rel=0.01)
    assert abs(force[0]) < 0.01 * weight


def test_taps(gransim):
    sim = gransim.Simulation(conftest.tiny_tapping())
    assert sim.tap == -1  # settling
    m0 = sim.run_to_tap(0)
    assert m0["tap"] == 0 and m0["t"] == pytest.approx(0.6, abs=1e-3)
    m1 = sim.run_to_tap(1)
    assert m1["tap"] == 1 and m1["t"] > m0["t"]
    for m in (m0, m1):
        assert 0.5 < m["phi"] < 0.95
        assert m["max_speed"] < 0.05
    assert m1["phi"] == pytest.approx(sim.phi(), abs=0)
    with pytest.raises(gransim.InputError, match="tap 0 is past"):
        sim.run_to_tap(0)


def test_dict_scene_equals_file_scene(gransim):
    path = os.path.join(conftest.SOURCE_DIR, "scenes", "tap_small_negative_g.toml")
    with open(path, "rb") as f:
        doc = tomllib.load(f)
    from_file = gransim.load_scene(path)
    from_dict = gransim.load_scene(doc)
    assert from_dict.resolved == from_file.resolved
    assert from_dict.path == "<dict>"


def test_overrides(gransim):
    path = os.path.join(conftest.SOURCE_DIR, "scenes", "tap_small_negative_g.toml")
    a = gransim.load_scene(path, set={"drive.g_p": 8, "integrator.kind": "gear6"})
    b = gransim.load_scene(path, set=["drive.g_p=8", 'integrator.kind="gear6"'])
    assert a.resolved["drive.g_p"] == "8.0"
    assert a.resolved["integrator.kind"] == '"gear6"'
    assert a.resolved == b.resolved
    c = gransim.load_scene(conftest.one_disk(), set={"drive.g": 1.62})
    assert c.resolved["drive.g"] == "1.62"


def test_bad_key_raises_input_error_like_the_cli(gransim, binary, tmp_path):
    path = os.path.join(conftest.SOURCE_DIR, "scenes", "tap_small_negative_g.toml")
    with pytest.raises(gransim.InputError) as err:
        gransim.Simulation(path, set={"drive.gp": 3})
    e = err.value
    assert isinstance(e, ValueError)
    assert e.key == "drive.gp"
    assert "drive.gp" in str(e) and "did you mean 'g_p'" in str(e)
    cli = subprocess.run([binary, "run", path, "--set", "drive.gp=3", "--out", str(tmp_path / "r")],
                         capture_output=True, text=True, env={**os.environ, "OMP_NUM_THREADS": "1"})
    assert cli.returncode == 2
    assert str(e) in cli.stderr


def test_bad_value_in_dict_names_key_and_line(gransim):
    doc = conftest.one_disk()
    doc["integrator"]["dt"] = -1.0
    with pytest.raises(gransim.InputError) as err:
        gransim.Simulation(doc)
    assert err.value.key == "integrator.dt"
    assert str(err.value).startswith("<dict>:")
    text = gransim.scene_toml(doc)
    line = next(i for i, s in enumerate(text.splitlines(), 1) if s.startswith("dt = "))
    assert err.value.where == f"<dict>:{line}"


def test_unstable_time_step_refused(gransim):
    with pytest.raises(gransim.InputError) as err:
        gransim.Simulation(conftest.one_disk(dt=5e-3))
    assert err.value.key == "integrator.dt"


def test_missing_file(gransim):
    with pytest.raises(gransim.InputError, match="no_such_scene.toml"):
        gransim.load_scene("no_such_scene.toml")

# a state set from Python: set positions and velocities give the exact free flight that
# follows, bad values are refused before anything changes, snapshots round-trip, a checkpoint
# continues bitwise, and the snapshot and trajectory files open in the field's readers
import os

import numpy as np
import pytest

import conftest


def test_set_state_then_free_fall_is_exact(gransim):
    sim = gransim.Simulation(conftest.one_disk(y0=0.8, dt=1e-5))
    y_view = sim.y
    sim.step(100)
    # throw the disk sideways and up from another place: velocity Verlet is exact for a
    # constant force, so the flight after the edit is the parabola from the new state
    sim.positions = [[0.3, 0.5]]
    sim.velocities = np.array([[0.2, 1.5]])
    assert np.shares_memory(y_view, sim.y) and y_view[0] == 0.5  # views stay valid
    t0 = sim.t
    sim.step(1000)
    t = sim.t - t0
    assert sim.x[0] == pytest.approx(0.3 + 0.2 * t, abs=1e-12)
    assert sim.y[0] == pytest.approx(0.5 + 1.5 * t - 0.5 * 9.81 * t * t, abs=1e-12)
    assert sim.vy[0] == pytest.approx(1.5 - 9.81 * t, abs=1e-12)
    assert sim.step_count == 1100


def test_bad_state_is_refused_and_nothing_changes(gransim):
    sim = gransim.Simulation(conftest.disk_pile(n_big=2, n_small=2))
    before = sim.get_snapshot()
    bad = [
        (dict(positions=np.zeros((3, 2))), "N×2"),                      # wrong count
        (dict(positions=[[0.05, 0.1]] * 3 + [[np.nan, 0.1]]), "not finite"),
        (dict(positions=[[0.05, 0.1]] * 3 + [[0.2, 0.1]]), "outside the box"),
        (dict(velocities=np.zeros(4)), "N×2"),
        (dict(theta=np.zeros((4, 2))), "1-D"),
        (dict(omega=[0, 0, np.inf, 0]), "not finite"),
    ]
    for kwargs, words in bad:
        with pytest.raises(gransim.InputError, match=words):
            sim.set_state(positions=kwargs.get("positions"), velocities=kwargs.get("velocities"),
                          theta=kwargs.get("theta"), omega=kwargs.get("omega"))
    after = sim.get_snapshot()
    for k in ("positions", "velocities", "theta", "omega"):
        assert np.array_equal(before[k], after[k]), k


def test_spin_only_where_rotation_is_integrated(gransim):
    # soft disks (Model S) never integrate θ and ω: a spin set there would be lost silently
    disk = gransim.Simulation(conftest.one_disk())
    with pytest.raises(gransim.InputError, match="rotation"):
        disk.omega = [3.0]
    disk.omega = [0.0]
    # decagons with friction do: the spin set is the spin the next step starts from
    pile = gransim.Simulation(conftest.tiny_tapping())
    spin = np.linspace(-2.0, 2.0, len(pile))
    pile.omega = spin
    pile.theta = np.full(len(pile), 0.25)
    assert np.array_equal(pile.omega, spin) and np.all(pile.theta == 0.25)


def test_snapshot_round_trip(gransim):
    sim = gransim.Simulation(conftest.disk_pile(n_big=3, n_small=3))
    sim.step(200)
    snap = sim.get_snapshot()
    assert snap["positions"].shape == (6, 2) and snap["species_names"] == ["big", "small"]
    assert snap["step"] == 200 and snap["t"] == pytest.approx(200 * 2e-5)
    sim.step(300)
    # the grains go back; the clock stays (a snapshot does not set time)
    snap.pop("t"), snap.pop("step")
    sim.set_snapshot(snap)
    assert np.array_equal(sim.positions, snap["positions"])
    assert np.array_equal(sim.velocities, snap["velocities"])
    assert sim.step_count == 500
    wrong = dict(snap, species=snap["species"][::-1])
    with pytest.raises(gransim.InputError, match="species"):
        sim.set_snapshot(wrong)
    with pytest.raises(gransim.InputError, match="clock"):
        sim.set_snapshot(dict(snap, step=7))


def test_checkpoint_continues_bitwise(gransim, tmp_path):
    a = gransim.Simulation(conftest.tiny_tapping())
    a.step(3000)
    path = tmp_path / "pile.gsck"
    a.save(path)
    b = gransim.Simulation.from_checkpoint(path)
    assert isinstance(b, gransim.Simulation) and b.step_count == 3000 and b.t == a.t
    a.step(2000)
    b.step(2000)
    for k in ("x", "y", "vx", "vy", "theta", "omega"):
        assert np.array_equal(getattr(a, k), getattr(b, k)), k
    assert b.tap == a.tap
    with pytest.raises(FileNotFoundError):
        gransim.Simulation.from_checkpoint(tmp_path / "nope.gsck")


def test_snapshot_and_trajectory_files(gransim, tmp_path):
    sim = gransim.Simulation(conftest.disk_pile(n_big=4, n_small=4))
    sim.step(100)
    sim.write_snapshot(tmp_path / "pile.vtp")
    sim.write_snapshot(tmp_path / "pile.xyz")
    sim.write_snapshot(tmp_path / "contacts.csv")
    with pytest.raises(gransim.InputError, match=".vtp"):
        sim.write_snapshot(tmp_path / "pile.png")
    with sim.trajectory(tmp_path / "traj.xyz") as tr:
        for _ in range(3):
            tr.write(sim)
            sim.step(50)
    assert tr.frames == 3
    text = (tmp_path / "pile.vtp").read_text()
    assert "<PolyData>" in text and 'NumberOfPolys="8"' in text
    # the trajectory as ASE reads it, when it is installed (tools/test.sh installs it)
    try:
        import ase.io
    except ImportError:
        lines = (tmp_path / "traj.xyz").read_text().splitlines()
        assert lines.count("8") == 3
        return
    frames = ase.io.read(tmp_path / "traj.xyz", index=":")
    assert len(frames) == 3 and len(frames[0]) == 8
    one = ase.io.read(tmp_path / "pile.xyz")
    assert np.allclose(one.positions[:, :2], sim.positions, atol=0.01)  # 150 steps later


def test_scene_to_dict_is_typed(gransim):
    scene = gransim.load_scene(conftest.tiny_tapping())
    d = scene.to_dict()
    assert d["drive.g_p"] == 4.0 and isinstance(d["drive.g_p"], float)
    assert d["scene.name"] == "tiny_tapping"
    assert d["box.lid"] is False
    assert isinstance(d["preparation.seed"], int) and d["preparation.seed"] == 7
    assert d["output.test_rect"] == [0.01, 0.005, 0.07, 0.04]
    assert set(d) == set(scene.resolved)


def test_missing_paths_are_file_not_found(gransim, tmp_path):
    missing = tmp_path / "nope"
    for call in (lambda: gransim.Simulation(str(missing) + ".toml"),
                 lambda: gransim.load_scene(missing),
                 lambda: gransim.read_png(str(missing) + ".png"),
                 lambda: gransim.read_run(missing),
                 lambda: gransim.read_csv(str(missing) + ".csv")):
        with pytest.raises(FileNotFoundError) as e:
            call()
        assert "nope" in str(e.value)
    assert os.path.exists(conftest.SOURCE_DIR)


def test_h5md_trajectory_written_from_python_and_read_lazily(gransim, tmp_path):
    h5py = pytest.importorskip("h5py")
    sim = gransim.Simulation(conftest.disk_pile(n_big=4, n_small=4))
    want = []
    with sim.trajectory(tmp_path / "traj.h5md") as tr:
        assert isinstance(tr, gransim.H5mdTrajectoryWriter)
        for _ in range(3):
            tr.write(sim)
            want.append((sim.t, sim.positions.copy(), sim.velocities.copy()))
            sim.step(50)
    assert tr.frames == 3
    # append=True goes on after the frames already there
    with sim.trajectory(tmp_path / "traj.h5md", append=True) as tr:
        tr.write(sim)
        want.append((sim.t, sim.positions.copy(), sim.velocities.copy()))
    assert tr.frames == 4
    with h5py.File(tmp_path / "traj.h5md", "r") as f:
        assert f["particles/all/position/value"].shape == (4, 8, 3)
    # read back through read_run's reader: the datasets are h5py's, read frame by frame
    os.rename(tmp_path / "traj.h5md", tmp_path / "trajectory.h5md")
    run = gransim.read_run(tmp_path)
    assert "trajectory.h5md" in run and run.loaded() == []
    traj = run["trajectory.h5md"]
    assert isinstance(traj.positions, h5py.Dataset) and len(traj) == 4
    for k, (t, pos, vel) in enumerate(want):
        assert traj.time[k] == t
        np.testing.assert_array_equal(traj.positions[k][:, :2], pos)
        np.testing.assert_array_equal(traj.velocities[k][:, :2], vel)
    frame = traj.frame(-1)
    np.testing.assert_array_equal(frame[["x", "y"]].to_numpy(), want[-1][1])
    assert set(frame.species) == {"big", "small"} and frame.attrs["box"] == (0.1, 0.3)
    with pytest.raises(IndexError):
        traj.frame(4)
    traj.close()
    # .h5 names H5MD as well; anything else is extended XYZ
    assert isinstance(sim.trajectory(tmp_path / "t.h5"), gransim.H5mdTrajectoryWriter)
    assert isinstance(sim.trajectory(tmp_path / "t.xyz"), gransim.TrajectoryWriter)

# a Simulation made from a scene with preparation.from_state starts from the saved grains, as
# `gransim run` does: the counts it leaves out are the state's, a checkpoint continues bitwise,
# and a mismatch is an InputError naming the key
import numpy as np
import pytest

import conftest


def forked(scene, path, **species_counts):
    s = dict(scene)
    s["preparation"] = {"from_state": str(path)}
    s["species"] = [dict(sp) for sp in scene["species"]]
    for sp in s["species"]:
        sp.pop("count", None)
        if sp["name"] in species_counts:
            sp["count"] = species_counts[sp["name"]]
    return s


def test_a_checkpoint_fork_continues_bitwise(gransim, tmp_path):
    a = gransim.Simulation(conftest.tiny_tapping())
    a.step(3000)
    path = tmp_path / "pile.gsck"
    a.save(path)
    b = gransim.Simulation(forked(conftest.tiny_tapping(), path))
    assert b.scene.to_dict()["species[0].count"] == 10  # the state's count, left out
    assert b.step_count == 0 and len(b.x) == len(a.x) == 22
    for k in ("x", "y", "vx", "vy", "theta", "omega"):
        assert np.array_equal(getattr(a, k), getattr(b, k)), k


def test_a_count_that_disagrees_names_the_key(gransim, tmp_path):
    a = gransim.Simulation(conftest.tiny_tapping())
    path = tmp_path / "pile.gsck"
    a.save(path)
    with pytest.raises(gransim.InputError, match=r"species\[0\]\.count"):
        gransim.Simulation(forked(conftest.tiny_tapping(), path, big=9))
    with pytest.raises(gransim.InputError, match="preparation.from_state"):
        gransim.Simulation(forked(conftest.tiny_tapping(), tmp_path / "nope.gsck"))

# NumPy views onto the simulation's arrays across its spatial sorts: a view taken before a sort
# is still the same quantity after it, slot for slot with the ids (never another array's values)
import numpy as np

import conftest


def test_views_follow_the_sort(gransim):
    scene = conftest.disk_pile(n_big=30, n_small=30)
    sim = gransim.Simulation(scene, set={"integrator.sort_every": 20})
    assert sim.sort_every == 20
    views = {name: getattr(sim, name) for name in
             ("x", "y", "vx", "vy", "theta", "omega", "radius", "mass", "species", "ids")}
    generation = sim.order_generation
    sim.step(200)
    assert sim.order_generation > generation, "no sort happened"
    # every old view shows what a fresh one shows: the same array, slot for slot
    for name, v in views.items():
        assert np.array_equal(v, getattr(sim, name)), name
    # and the slots agree with each other: a grain's radius and species travel with its id
    radius_of = {}
    for i, r, s in zip(views["ids"], views["radius"], views["species"]):
        radius_of.setdefault(int(s), set()).add(float(r))
    assert all(len(r) == 1 for r in radius_of.values()), radius_of
    # positions by id match the copies made now
    pos = sim.positions
    assert np.array_equal(pos[:, 0], views["x"]) and np.array_equal(pos[:, 1], views["y"])

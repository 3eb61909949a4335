# frames as NumPy images (the grains' colours where the grains are), PNG files and movies
import numpy as np
import pytest

import conftest


def settled_pile(gransim):
    sim = gransim.Simulation(conftest.disk_pile())
    sim.run(0.2)
    return sim


def pixel(sim, i, w, h, box):
    # camera = the box [0, 0, Lx, Ly] on a w×h image of the same aspect: row 0 at the top
    return int(sim.y[i] / box[1] * -h + h), int(sim.x[i] / box[0] * w)


def test_grains_have_their_colour_where_they_are(gransim):
    sim = settled_pile(gransim)
    lx, ly = sim.box
    w, h = 200, 600
    opts = dict(size=[w, h], camera=[0.0, 0.0, lx, ly], colorbar=False, clock=False,
                renderer="software")
    img = sim.render(color_by="species", colormap="viridis", range=[0, 1], **opts)
    assert img.shape == (h, w, 3) and img.dtype == np.uint8
    colours = {}
    for i in range(len(sim)):
        r, c = pixel(sim, i, w, h, (lx, ly))
        colours.setdefault(int(sim.species[i]), set()).add(tuple(img[r, c]))
    # every grain of a species has one colour, and the two species differ
    assert len(colours[0]) == 1 and len(colours[1]) == 1
    assert colours[0] != colours[1]
    # the empty top of the box is neither
    top = tuple(img[5, w // 2])
    assert top not in colours[0] | colours[1]
    # the grains cover as many pixels as their area says: more than their fill colour alone
    # (a dark outline runs along the rim), fewer than everything but the background
    uni = sim.render(color_by="uniform", **opts)
    r, c = pixel(sim, 0, w, h, (lx, ly))
    fill = np.all(uni == uni[r, c], axis=2).sum()
    drawn = (~np.all(uni == uni[5, w // 2], axis=2)).sum()
    area = np.pi * (sim.radius ** 2).sum() / (lx * ly) * w * h
    assert 0.7 * area < fill < area < drawn < 1.15 * area


def test_rgba_and_renderer_reuse(gransim):
    sim = settled_pile(gransim)
    r = sim.renderer(size=[64, 48], renderer="software")
    assert r.width == 64 and r.height == 48 and "software" in r.backend
    a = r.render(sim, channels=4)
    assert a.shape == (48, 64, 4) and (a[:, :, 3] == 255).all()
    b = r.render(sim, channels=3)
    assert np.array_equal(a[:, :, :3], b)


def test_bad_render_option_names_key(gransim):
    sim = gransim.Simulation(conftest.one_disk())
    with pytest.raises(gransim.InputError) as err:
        sim.render(color_by="temperature")
    assert err.value.key == "render.color_by"


def test_png_round_trip(gransim, tmp_path):
    sim = gransim.Simulation(conftest.one_disk())
    img = sim.render(size=[40, 30], renderer="software")
    path = str(tmp_path / "f.png")
    gransim.write_png(path, img)
    back = gransim.read_png(path, channels=3)
    assert np.array_equal(back, img)


@pytest.mark.skipif("not __import__('gransim').have_movie")
def test_movie(gransim, tmp_path):
    sim = gransim.Simulation(conftest.disk_pile(n_big=4, n_small=4))
    r = sim.renderer(size=[96, 64], renderer="software", color_by="uniform")

    def frames():
        for _ in range(6):
            sim.run(0.01)
            yield r.render(sim)

    path = tmp_path / "m.mp4"
    assert gransim.write_movie(path, frames(), fps=10, preset="ultrafast") == 6
    info = gransim.probe_movie(str(path))
    assert (info["width"], info["height"], info["frames"]) == (96, 64, 6)
    last = gransim.movie_frame(str(path), 5)
    assert last.shape == (64, 96, 3)
    # lossy, but close to the last frame drawn
    assert np.abs(last.astype(int) - r.render(sim).astype(int)).mean() < 8

"""gransim: 2D granular dynamics from Python (docs/python-module.md).

    import gransim
    sim = gransim.Simulation("scenes/tap_small_negative_g.toml", set={"drive.g_p": 8})
    sim.run(0.5)                      # simulated seconds
    x, y = sim.x, sim.y               # views onto the simulation's own arrays
    img = sim.render(width=640, height=360)

Scenes come from a file or a dict (written as TOML and parsed by the same parser, so errors
read the same as the command line's); errors in input raise gransim.InputError (a ValueError)
whose message names the file, line and key.
"""

import os

from . import _gransim
from ._gransim import (  # noqa: F401  (re-exported)
    HealthError,
    InputError,
    OutputError,
    Renderer,
    RenderError,
    Scene,
    autocorr_time,
    beta_from_phi,
    beta_from_volume,
    fit_quadron,
    have_movie,
    have_osmesa,
    mser_truncation,
    normality_chi2,
    quadron_gas_phi,
    quadron_lnz,
    quadron_phi,
    read_png,
    rfm,
    tap_analysis,
    write_png,
)
from ._toml import dumps as scene_toml, value_text as _value_text
from .run_dir import read_csv, read_run  # noqa: F401

__version__ = _gransim.__version__

__all__ = [
    "HealthError", "InputError", "OutputError", "RenderError", "Renderer", "Scene", "Simulation",
    "autocorr_time", "beta_from_phi", "beta_from_volume", "fit_quadron", "have_movie",
    "have_osmesa", "load_scene", "mser_truncation", "normality_chi2", "quadron_gas_phi", "quadron_lnz",
    "quadron_phi", "read_csv", "read_png", "read_run", "rfm", "scene_toml", "tap_analysis",
    "write_movie", "write_png",
]


def _overrides(set):
    """--set style overrides from a dict {key: value} (values written as TOML) or from
    'key=value' strings (the command line's syntax)"""
    if set is None:
        return []
    if isinstance(set, dict):
        return [f"{k}={_value_text(v)}" for k, v in set.items()]
    if isinstance(set, str):
        return [set]
    return [str(s) for s in set]


def load_scene(source, set=None, name="<dict>"):
    """a validated Scene from a scene file path, TOML text (a str holding a newline), a dict
    of tables, or a Scene (returned as is when there is nothing to override). `set` overrides
    keys as `gransim run --set` does: {"drive.g_p": 8} or ["drive.g_p=8"]."""
    overrides = _overrides(set)
    if isinstance(source, Scene):
        if not overrides:
            return source
        return _gransim.parse_scene_string(source.to_toml(), source.path, overrides)
    if isinstance(source, dict):
        return _gransim.parse_scene_string(scene_toml(source), name, overrides)
    if isinstance(source, str) and "\n" in source:
        return _gransim.parse_scene_string(source, name, overrides)
    return _gransim.parse_scene_file(os.fspath(source), overrides)


class Simulation(_gransim.Simulation):
    """a simulation set up as `gransim run` does: grains placed, protocol clock started, time
    step checked. `scene` is anything load_scene takes.

    Views (no copy, read-only, valid while the Simulation lives): x, y, vx, vy, theta, omega,
    species, radius, mass, ids. They show the state after every step without being fetched
    again, but a spatial sort (integrator.sort_every, see .sort_every and .order_generation)
    moves particles between slots and replaces the buffers: fetch the arrays again after one.
    Copies: positions, velocities (N×2), contacts()."""

    def __init__(self, scene, set=None):
        super().__init__(load_scene(scene, set))

    def render(self, channels=3, **options):
        """the current frame as an H×W×3 (or ×4) uint8 array. Keyword options are keys of
        the scene's [render] section (width=640, color_by="species", renderer="software", …)
        and are checked by the scene parser."""
        return Renderer(self, [f"render.{k}={_value_text(v)}" for k, v in options.items()]
                        ).render(self, channels)

    def renderer(self, **options):
        """a Renderer with these [render] options, to draw many frames (a movie)"""
        return Renderer(self, [f"render.{k}={_value_text(v)}" for k, v in options.items()])


def write_movie(path, frames, fps=30, crf=20, preset="medium", codec=""):
    """encode an iterable of H×W×3 (or ×4) uint8 frames of one size to an MP4 file; returns
    the number of frames written"""
    if not have_movie:
        raise RuntimeError("this gransim was built without FFmpeg: no movies")
    enc = None
    n = 0
    for frame in frames:
        if enc is None:
            h, w = frame.shape[:2]
            enc = _gransim.MovieEncoder(os.fspath(path), w, h, fps, crf, preset, codec)
        enc.add_frame(frame)
        n += 1
    if enc is None:
        raise ValueError("write_movie: no frames")
    enc.close()
    return n


if have_movie:
    MovieEncoder = _gransim.MovieEncoder
    probe_movie = _gransim.probe_movie
    movie_frame = _gransim.movie_frame
    __all__ += ["MovieEncoder", "movie_frame", "probe_movie"]

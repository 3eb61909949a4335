"""The part of the gransim package built on the compiled module: scenes, simulations, renders,
movies and the analyses of the C++ library. gransim/__init__.py exports it."""

import errno
import os

from . import _gransim
from ._gransim import (  # noqa: F401  (re-exported)
    H5mdTrajectoryWriter,
    HealthError,
    InputError,
    OutputError,
    Renderer,
    RenderError,
    Scene,
    TrajectoryWriter,
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
    rfm,
    tap_analysis,
    write_png,
)
from ._toml import dumps as scene_toml, loads_value as _loads_value, value_text as _value_text
from .run_dir import H5mdTrajectory, read_csv, read_run  # noqa: F401

__version__ = _gransim.__version__

__all__ = [
    "H5mdTrajectoryWriter", "HealthError", "InputError", "OutputError", "PathNotFoundError", "RenderError", "Renderer",
    "H5mdTrajectory", "Scene", "Simulation",
    "autocorr_time", "beta_from_phi", "beta_from_volume", "fit_quadron", "have_movie",
    "have_osmesa", "load_scene", "mser_truncation", "normality_chi2", "quadron_gas_phi", "quadron_lnz",
    "quadron_phi", "read_csv", "read_png", "read_run", "rfm", "scene_toml", "tap_analysis",
    "TrajectoryWriter", "write_movie", "write_png",
]


class PathNotFoundError(FileNotFoundError, InputError):
    """a path given to gransim does not exist: a FileNotFoundError, and an InputError (a
    ValueError) as every other bad input, with .where (the path) and .key (what it was for)"""


def _existing(path, what):
    """path as a str, or PathNotFoundError naming it"""
    path = os.fspath(path)
    if not os.path.exists(path):
        e = PathNotFoundError(errno.ENOENT, f"{what} not found", path)
        e.where, e.key = path, what
        raise e
    return path


def _scene_to_dict(self):
    """every key of the resolved scene (defaults included) with a typed value, as run.json's
    "scene" holds it: {"drive.g_p": 8.0, "scene.name": "demo", "box.lid": False, …}"""
    return {k: _loads_value(v) for k, v in self.resolved.items()}


Scene.to_dict = _scene_to_dict


def read_png(path, channels=4):
    """a PNG file as an H×W×channels uint8 array (channels 3 or 4)"""
    return _gransim.read_png(_existing(path, "PNG file"), channels)


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
    return _gransim.parse_scene_file(_existing(source, "scene file"), overrides)


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

    @classmethod
    def from_checkpoint(cls, path):
        """the simulation a checkpoint holds (Simulation.save, or a run's checkpoint-*.gsck):
        state, integrator history, contact springs and protocol clock, so that stepping on
        gives the same numbers as the run that saved it"""
        sim = cls.__new__(cls)
        _gransim.Simulation.__init__(sim, _gransim.read_checkpoint(_existing(path, "checkpoint")))
        return sim

    def trajectory(self, path, append=False):
        """a trajectory file to write frames of this simulation to, its format chosen by the
        extension: .h5md or .h5 give H5MD on HDF5 (h5py, MDAnalysis; H5mdTrajectoryWriter),
        any other extended XYZ (ASE, OVITO; TrajectoryWriter):
        `with sim.trajectory("t.h5md") as tr: … tr.write(sim)`"""
        path = os.fspath(path)
        if os.path.splitext(path)[1].lower() in (".h5md", ".h5"):
            return H5mdTrajectoryWriter(path, append)
        return TrajectoryWriter(path, append)

    def write_snapshot(self, path):
        """write the configuration now: .vtp (VTK PolyData with the grains' outlines,
        ParaView), .xyz (one extended-XYZ frame: ASE, OVITO) or .csv (one row per contact)"""
        return super().write_snapshot(os.fspath(path))

    def save(self, path):
        """write a checkpoint (complete state, integrator history, contact springs, protocol
        clock); Simulation.from_checkpoint(path) continues bitwise"""
        return super().save(os.fspath(path))

    # the state, with units; positions, velocities, theta and omega can be set (set_state)
    positions = property(_gransim.Simulation.positions.fget,
                         lambda self, v: self.set_state(positions=v),
                         doc="N×2 positions (x, y), m: a copy; assigning sets them (set_state)")
    velocities = property(_gransim.Simulation.velocities.fget,
                          lambda self, v: self.set_state(velocities=v),
                          doc="N×2 velocities (vx, vy), m/s: a copy; assigning sets them")
    theta = property(_gransim.Simulation.theta.fget, lambda self, v: self.set_state(theta=v),
                     doc="orientations θ, rad (view, read-only); assigning sets them")
    omega = property(_gransim.Simulation.omega.fget, lambda self, v: self.set_state(omega=v),
                     doc="angular velocities ω, rad/s (view, read-only); assigning sets them")
    x = property(_gransim.Simulation.x.fget, doc="x positions, m (view, read-only)")
    y = property(_gransim.Simulation.y.fget, doc="y positions, m (view, read-only)")
    vx = property(_gransim.Simulation.vx.fget, doc="x velocities, m/s (view, read-only)")
    vy = property(_gransim.Simulation.vy.fget, doc="y velocities, m/s (view, read-only)")
    species = property(_gransim.Simulation.species.fget,
                       doc="species index of each particle (view; names: species_names)")
    radius = property(_gransim.Simulation.radius.fget, doc="circumradius, m (view)")
    mass = property(_gransim.Simulation.mass.fget, doc="mass, kg (view)")
    ids = property(_gransim.Simulation.ids.fget,
                   doc="each slot's particle label, its placement index (view)")
    t = property(_gransim.Simulation.t.fget, doc="simulated time, s")
    dt = property(_gransim.Simulation.dt.fget, doc="time step Δt, s")
    step_count = property(_gransim.Simulation.step_count.fget, doc="time steps taken")
    box = property(_gransim.Simulation.box.fget,
                   doc="(width, height) of the box (periodic: the period), m")
    gravity = property(_gransim.Simulation.gravity.fget,
                       doc="(gx, gy) applied during the last step, m/s²")
    kinetic_energy = property(_gransim.Simulation.kinetic_energy.fget,
                              doc="translational + rotational kinetic energy, J")

    def render(self, channels=3, **options):
        """the current frame as an H×W×3 (or ×4) uint8 array. Keyword options are keys of
        the scene's [render] section (size=[640, 360], color_by="species",
        renderer="software", …) and are checked by the scene parser."""
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


for _obj in (PathNotFoundError, Simulation, load_scene, read_png, write_movie):
    _obj.__module__ = "gransim"
del _obj

"""gransim: 2D granular dynamics from Python (docs/python-module.md).

>>> import gransim
>>> sim = gransim.Simulation("scenes/tap_small_negative_g.toml", set={"drive.g_p": 8})
>>> sim.run(0.05)                           # simulated seconds
>>> sim.step_count, len(sim)                # time steps (Δt = 5e-5 s) and grains
(1000, 250)
>>> sim.x.shape, sim.positions.shape        # a view onto the simulation's own array, a copy; m
((250,), (250, 2))
>>> sim.set_state(velocities=0 * sim.velocities, omega=0 * sim.omega)   # checked, then set
>>> sim.kinetic_energy                      # J
0.0
>>> sim.render(size=[160, 90]).shape        # H×W×3 uint8
(90, 160, 3)
>>> gransim.load_scene("scenes/demo.toml").to_dict()["integrator.dt"]   # typed scene values, s
5e-05

Scenes come from a file or a dict (written as TOML and parsed by the same parser, so errors
read the same as the command line's); errors in input raise gransim.InputError (a ValueError)
whose message names the file, line and key.

The analyses' charts (gransim.charts) and the reproduction's verdicts and report
(gransim.reproduce) are pure Python (numpy, matplotlib): they import without the compiled
module, so `gransim analyze` and `gransim reproduce` run them under any python3 that has those.
"""

try:
    from . import _gransim  # noqa: F401
except ImportError as _missing:
    import os as _os
    import sys as _sys

    _compiled_error = _missing
    # a file absent reads as "cannot import name": say which interpreter and folder instead
    _why = (f"none built for {_sys.executable} in {_os.path.dirname(__file__)}"
            if "cannot import name" in str(_missing) else str(_missing))
    _PURE = ("charts", "reproduce", "render_snapshot", "run_dir")

    def __getattr__(name):
        # submodules must read as absent (AttributeError) for `from gransim import charts`
        if name.startswith("__") or name in _PURE:
            raise AttributeError(f"module 'gransim' has no attribute {name!r}")
        raise ImportError(f"gransim.{name} needs the compiled module gransim._gransim ({_why}); "
                          "gransim.charts and gransim.reproduce work without it") \
            from _compiled_error
else:
    from ._api import *  # noqa: F401,F403
    from ._api import __all__, __version__  # noqa: F401

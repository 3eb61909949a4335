# shared scenes of the Python module's tests: small dicts, each a few seconds at most
import os
import sys

import pytest

SOURCE_DIR = os.environ.get("GS_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def disk_material():
    return {"name": "disk", "ks": 5e5, "eps_n": 0.5, "eps_t": 0.5, "mu": 0.5}


def one_disk(y0=0.8, dt=1e-5):
    """one disk of radius 1 cm at rest in a 1 m box under gravity"""
    return {
        "scene": {"name": "free_fall", "duration": 0.1},
        "model": {"kind": "S"},
        "material": [disk_material()],
        "species": [{"name": "disk", "shape": "disk", "radius": 0.01, "mass": 0.01}],
        "box": {"kind": "walls", "width": 1.0, "height": 1.0},
        "preparation": {"particle": [{"species": "disk", "x": 0.5, "y": y0}]},
        "integrator": {"kind": "velocity_verlet", "dt": dt},
        "drive": {"kind": "gravity", "g": 9.81},
    }


def disk_pile(n_big=12, n_small=12):
    """two species of disks dropped into a 0.1 m box"""
    return {
        "scene": {"name": "disk_pile", "duration": 0.5},
        "model": {"kind": "S"},
        "material": [disk_material()],
        "species": [
            {"name": "big", "shape": "disk", "radius": 0.006, "mass": 0.01, "count": n_big},
            {"name": "small", "shape": "disk", "radius": 0.004, "mass": 0.005, "count": n_small},
        ],
        "box": {"kind": "walls", "width": 0.1, "height": 0.3},
        "preparation": {"placement": "loose_column", "seed": 3, "settle_time": 0.0},
        "integrator": {"kind": "velocity_verlet", "dt": 2e-5},
        "drive": {"kind": "gravity", "g": 9.81},
    }


def tiny_tapping():
    """a few decagons tapped by negative-g pulses: quick taps with early rest"""
    return {
        "scene": {"name": "tiny_tapping"},
        "model": {"kind": "P"},
        "material": [{"name": "grain", "E": 1000.0, "gamma": 0.5, "mu": 0.6}],
        "species": [
            {"name": "big", "radius": 0.009, "count": 10, "density": 1.0},
            {"name": "small", "radius": 0.00636, "count": 12, "density": 1.0},
        ],
        "box": {"kind": "walls", "width": 0.08, "height": 0.5, "lid": False},
        "preparation": {"placement": "loose_column", "seed": 7, "settle_time": 0.6},
        "integrator": {"kind": "velocity_verlet", "dt": 5e-5},
        "drive": {"kind": "negative_g", "g_p": 4.0, "t1": 0.01, "period": 1.0, "taps": 5,
                  "early_rest": True, "rest_speed": 2e-3, "rest_energy": 1e-6, "rest_hold": 0.05},
        "output": {"test_rect": [0.01, 0.005, 0.07, 0.04]},
    }


@pytest.fixture(scope="session")
def gransim():
    import gransim as g
    return g


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("GS_BINARY")
    if not path or not os.path.exists(path):
        pytest.skip("GS_BINARY is not set")
    return path


sys.path.insert(0, os.path.dirname(__file__))

"""Small scenes shared by the Python tests of the tools: a pile of 40 decagons (18 big, 22
small) in a 0.1 m box, tapped by 0.01 s pulses of 2 g, that taps in seconds."""


def tiny_tapping(period, taps, extra=""):
    """the pile tapped `taps` times with period `period` (s); `extra` is appended TOML"""
    return f"""
[scene]
name = "tiny_tapping"
[[material]]
name = "grain"
[[species]]
name = "big"
radius = 0.009
count = 18
[[species]]
name = "small"
radius = 0.00636
count = 22
[box]
width = 0.1
height = 0.5
[preparation]
seed = 5
settle_time = 0.5
[integrator]
kind = "velocity_verlet"
dt = 1e-4
[drive]
kind = "negative_g"
g_p = 2.0
t1 = 0.01
period = {period}
taps = {taps}
[output]
test_rect = [0.01, 0.01, 0.09, 0.05]
discard_taps = 2
series_every = 500
""" + extra

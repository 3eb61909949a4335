"""Teaching example: a small pile of decagons tapped five times.

The pile settles, then five pulses of negative gravity lift it; after each tap it comes to rest
and the volume fraction φ of the test rectangle is measured, as `gransim run` writes it to
taps.csv. The script plots φ against the tap number and saves one frame of the pile.

    PYTHONPATH=build/python python3 docs/examples/tap_five_times.py --out /tmp/taps

writes /tmp/taps/phi_per_tap.png and /tmp/taps/pile.png (about half a minute on one core;
--grains 30 makes it a few seconds).
"""

import argparse
import os

import matplotlib

matplotlib.use("Agg")  # files only, no window
import matplotlib.pyplot as plt  # noqa: E402

import gransim  # noqa: E402


def small_pile(grains, g_p):
    """scenes/tap_small_negative_g.toml made smaller: fewer grains in a narrower box"""
    big = grains * 115 // 250
    width = 0.24 * max(grains / 250, 0.15) ** 0.5
    return {
        "scene": {"name": "tap_five_times"},
        "model": {"kind": "P"},
        "material": [{"name": "grain", "E": 1000.0, "gamma": 0.5, "mu": 0.6}],
        "species": [
            {"name": "big", "radius": 0.009, "count": big, "density": 1.0},
            {"name": "small", "radius": 0.00636, "count": grains - big, "density": 1.0},
        ],
        "box": {"kind": "walls", "width": width, "height": 0.6, "lid": False},
        "preparation": {"placement": "loose_column", "seed": 7, "settle_time": 1.0},
        "integrator": {"kind": "velocity_verlet", "dt": 5e-5},
        "drive": {"kind": "negative_g", "g_p": g_p, "t1": 0.01, "period": 2.0, "taps": 5,
                  "early_rest": True, "rest_speed": 2e-3, "rest_energy": 1e-6, "rest_hold": 0.05},
        # φ is measured away from the walls and the free surface
        "output": {"test_rect": [0.02, 0.01, width - 0.02, 0.03 + 0.0004 * grains]},
        "render": {"color_by": "species", "colormap": "coolwarm", "colorbar": False},
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="tap_five_times", help="folder for the two PNG files")
    ap.add_argument("--grains", type=int, default=120, help="number of grains")
    ap.add_argument("--g-p", type=float, default=6.0, help="pulse strength, units of g")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)

    sim = gransim.Simulation(small_pile(args.grains, args.g_p))
    rows = [sim.run_to_tap(k) for k in range(6)]  # the settled pile, then after each tap
    for r in rows:
        print(f"tap {r['tap']}: t = {r['t']:.3f} s, phi = {r['phi']:.4f}")

    fig, ax = plt.subplots(figsize=(5, 3.2), dpi=120)
    ax.plot([r["tap"] for r in rows], [r["phi"] for r in rows], "o-", color="tab:blue")
    ax.set_xlabel("tap")
    ax.set_ylabel("volume fraction φ")
    ax.set_title(f"{len(sim)} decagons, pulses of {args.g_p:g} g")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "phi_per_tap.png"))

    # the pile after the fifth tap, framed on its lower part
    lx, _ = sim.box
    top = max(float(sim.y.max()) + 0.03, 0.1)
    frame = sim.render(size=[480, int(480 * (top + 0.02) / (lx + 0.04))],
                       camera=[-0.02, -0.01, lx + 0.02, top + 0.01])
    gransim.write_png(os.path.join(args.out, "pile.png"), frame)


if __name__ == "__main__":
    main()

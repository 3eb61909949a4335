#!/usr/bin/env python3
"""The harness's final table: every whole-scene figure, its target and whether it is met.

usage: summary.py RESULTS_DIR
  gb_1t.json, gb_2t.json, gb_scaling.json  Google Benchmark JSON (1 thread, 2 threads, N scan)
  results.txt                              "key value" lines of compare_lammps.sh and taps.sh
Missing inputs give "–" rows. Targets are reported, never asserted (exit status 0).
"""
import json
import math
import os
import sys

d = sys.argv[1]


def gb(name):
    """name → benchmark entry; where a benchmark ran repeated, its median aggregate (with its
    counters), and the repetitions' smallest real time under min_real_time"""
    try:
        with open(os.path.join(d, name)) as fh:
            runs = [b for b in json.load(fh).get("benchmarks", []) if not b.get("error_occurred")]
    except (OSError, ValueError):
        return {}
    table, times = {}, {}
    for b in runs:
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                table[b["run_name"]] = dict(b, name=b["run_name"])
            continue
        times.setdefault(b["name"], []).append(b["real_time"])
        table.setdefault(b["name"], b)
    for n, t in times.items():
        if n in table:
            table[n]["min_real_time"] = min(t)
            table[n]["repetitions"] = len(t)
    return table


g1, g2, gs = gb("gb_1t.json"), gb("gb_2t.json"), gb("gb_scaling.json")
g_ring = gb("gb_ring.json") or g1  # the ring repeated (older runs: within gb_1t.json)
kv = {}
try:
    with open(os.path.join(d, "results.txt")) as fh:
        for line in fh:
            k, _, v = line.partition(" ")
            try:
                kv[k] = float(v)
            except ValueError:
                pass
except OSError:
    pass


def counter(table, name, key="particle-steps/s"):
    b = table.get(name)
    return b.get(key) if b else None


def ratio(a, b):
    return a / b if a is not None and b is not None and b > 0 and not math.isnan(b) else None


rows = []  # (figure, value text, target text, verdict)


def fmt(v, unit=""):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    return (f"{v:.3g}" if abs(v) < 1e4 else f"{v:.3g}".replace("e+0", "e")) + unit


def row(figure, v, unit="", target=None, ok=None, note=""):
    # a figure with a target but no value (its benchmark failed or was skipped): "not measured"
    verdict = "–" if ok is None else "not measured" if v is None else ("met" if ok(v) else "NOT met")
    rows.append((figure, fmt(v, unit) + note, target or "(info)", verdict))


quick = kv.get("tap.paper.quick") == 1
ge = lambda t: (lambda v: v >= t)
le = lambda t: (lambda v: v <= t)



def pile_entry(table, label):  # BM_PileStep by its label "integrator/broad phase"
    for name, b in table.items():
        if name.startswith("BM_PileStep/") and b.get("label") == label:
            return b
    return {}


def pile(table, label):  # its particle-steps per second (the median's, where repeated)
    return pile_entry(table, label).get("particle-steps/s")


def reps_note(b, target, ok):
    """a repeated benchmark entry: how many repetitions, and the particle-steps per second of
    the fastest (the median's rate scaled by median time ÷ smallest time)"""
    v, t = b.get("particle-steps/s"), b.get("min_real_time")
    if not b.get("repetitions") or v is None or not t:
        return ""
    fast = v * b["real_time"] / t
    met = ": " + target if ok(fast) else ""
    return f" (median of {b['repetitions']}; fastest {fmt(fast)}{met})"


# the settled paper pile (Google Benchmark whole steps)
for bp, bpname in (("box2d_tree", "Box2D tree"), ("cell_grid", "cell grid")):
    row(f"1184-decagon pile, Gear 6, {bpname}, 1 thread", pile(g1, "gear6/" + bp), " p-st/s")
    row(f"1184-decagon pile, Gear 6, {bpname}, 2 threads", pile(g2, "gear6/" + bp), " p-st/s",
        "≥ 5e6 p-st/s", ge(5e6), note=reps_note(pile_entry(g2, "gear6/" + bp), "≥ 5e6", ge(5e6)))
row("1184-decagon pile, velocity Verlet, 2 threads", pile(g2, "velocity_verlet/box2d_tree"), " p-st/s")
# the overlap kernel on the settled pile's own pairs, ns per pair (the step's largest part)
ov = g1.get("BM_PileOverlaps", {})
row("decagon overlap on the settled pile's pairs, 1 thread",
    1e9 / ov["items_per_second"] if ov.get("items_per_second") else None, " ns per pair")

# gransim against LAMMPS
for sc, label in (("settled", "10⁴ disks settled under gravity"), ("fluid", "10⁴-disk forced fluid")):
    p = f"lammps.{sc}."
    row(f"{label}: gransim, 1 / 2 threads", kv.get(p + "gransim1"), " p-st/s",
        note=f" / {fmt(kv.get(p + 'gransim2'))}")
    row(f"{label}: LAMMPS, 1 / 2 ranks", kv.get(p + "lammps1"), " p-st/s",
        note=f" / {fmt(kv.get(p + 'lammps2'))}")
    row(f"{label}: gransim/LAMMPS per core", ratio(kv.get(p + "gransim1"), kv.get(p + "lammps1")),
        "×", "≥ 2×", ge(2.0))
    row(f"{label}: gransim/LAMMPS per core, paired (same time, CPUs swapped)", kv.get(p + "paired"),
        "×", "≥ 2×", ge(2.0))
    row(f"{label}: gransim/LAMMPS on 2 cores", ratio(kv.get(p + "gransim2"), kv.get(p + "lammps2")),
        "×")

# Random Force Model
ring = "BM_Rfm1DRingStep/0/min_time:3.000"
row("1D ring (N = 1000), 1 thread", counter(g_ring, ring), " p-st/s", "≥ 1e8 p-st/s", ge(1e8),
    note=reps_note(g_ring.get(ring, {}), "≥ 1e8", ge(1e8)))
row("2D RFM reference fluid (N = 2000), 1 thread",
    counter(g1, "BM_Rfm2DReferenceStep/0/min_time:3.000"), " p-st/s")

# cost flatness: medians of interleaved repetitions (the ratio of the minima in the note)
base = counter(gs, "BM_FluidCostScaling/10000/real_time")
base_min = gs.get("BM_FluidCostScaling/10000/real_time", {}).get("min_real_time")
for n in (1000, 10000, 100000, 1000000):
    name = f"BM_FluidCostScaling/{n}/real_time"
    v = counter(gs, name)
    rel = ratio(base, v)  # cost per particle-step relative to N = 10⁴
    t_min = gs.get(name, {}).get("min_real_time")
    rel_min = ratio(t_min * 1e4 / n, base_min) if t_min is not None and base_min else None
    reps = gs.get(name, {}).get("repetitions", 1)
    row(f"forced fluid N = 1e{round(math.log10(n))}: cost per particle-step ÷ N = 1e4's", rel, "",
        "0.75…1.25" if n != 10000 else None,
        (lambda x: 0.75 <= x <= 1.25) if n != 10000 else None,
        note=f" ({fmt(v)} p-st/s, 1 thread; median of {reps}"
             + (f", minima {fmt(rel_min)}" if n != 10000 else "") + ")")
mixed = counter(gs, "BM_FluidMixedOrder/1000000/real_time")
row("forced fluid N = 1e6, particles numbered at random (an unsorted long run): cost ÷ N = 1e4's",
    ratio(base, mixed), "", note=f" ({fmt(mixed)} p-st/s; the spatial sort keeps the figure above)")
for arg, what in ((0, "from the random order, fresh buffers"),
                  (1, "of the sorted state, buffers kept (every 1000 steps in a run)")):
    t = gs.get(f"BM_SortParticles/1000000/{arg}/iterations:3", {}).get("real_time")
    row(f"one spatial sort of 1e6 disks {what}", t, " ms")

# seconds per tap
ext = " (extrapolated ×10)" if quick else ""
row("paper tap (3 s), fixed period, Gear 6, 1 thread", kv.get("tap.paper.fixed.t1"), " s", note=ext)


def runs_note(key, target):  # a repeated tap figure: how many runs, the fastest
    n, fast = kv.get(key + ".runs"), kv.get(key + ".min")
    if not n or fast is None:
        return ""
    return (f" (median of {n:.0f} runs; fastest {fmt(fast)} s"
            f"{': ≤ ' + fmt(target) if fast <= target else ''})")


row("paper tap (3 s), fixed period, Gear 6, 2 threads", kv.get("tap.paper.fixed.t2"), " s",
    "≤ 15 s", le(15.0), note=ext + runs_note("tap.paper.fixed.t2", 15.0))
row("paper tap, whole run, Gear 6, 2 threads", kv.get("tap.paper.fixed.rate.t2"), " p-st/s")
# the window control (taps.sh): the same host moment in the tap's units. A tap step as dear as
# the settled pile's step measured just before means a slow tap is the host's slow spell
row("paper tap, 2 threads: µs per step / the settled pile's step just before each run",
    kv.get("tap.paper.fixed.t2.step_us"), " µs",
    note=f" / {fmt(kv.get('tap.paper.fixed.t2.control_us'), ' µs')} (medians)")


def ends(key):  # how many relaxations ended early
    v = kv.get(key)
    return " (skipped: QUICK)" if quick and v is None else "" if v is None else f" ({v:.0f} early ends)"


row("paper tap, early rest (_fast.toml: VV 1/7500 s), 1 thread", kv.get("tap.paper.rest.t1"), " s",
    note=ends("tap.paper.rest.early.t1"))
row("paper tap, early rest (_fast.toml: VV 1/7500 s), 2 threads", kv.get("tap.paper.rest.t2"), " s",
    "≤ 5 s", le(5.0), note=ends("tap.paper.rest.early.t2") + runs_note("tap.paper.rest.t2", 5.0))
row("small pile (250) tap, fixed period, 1 thread", kv.get("tap.small.fixed.t1"), " s")
row("small pile (250) tap, early rest, 1 thread", kv.get("tap.small.rest.t1"), " s",
    note=ends("tap.small.rest.early.t1"))

# MPI sweep
s1, s2 = kv.get("sweep.serial_s"), kv.get("sweep.mpi2_s")
row("sweep of 4 small-pile runs: serial / mpirun -np 2", s1, " s", note=f" / {fmt(s2, ' s')}")
row("sweep speed-up on 2 ranks", ratio(s1, s2), "×", "(ideal 2×)")

# frames per second (every benchmark with an fps counter)
for name, b in list(g1.items()):
    if "fps" in b:
        row(f"frames: {name.removeprefix('BM_').split('/real_time')[0]}", b["fps"], " fps")


def machine():
    """machine.txt (bench/machine.sh) as one line; AMD's x86 families named by core generation"""
    m = {}
    try:
        with open(os.path.join(d, "machine.txt")) as fh:
            for line in fh:
                k, _, v = line.rstrip("\n").partition(" ")
                m[k] = v
    except OSError:
        return None
    gen = ""
    try:
        fam, mod = int(m.get("family", "")), int(m.get("model", ""))
        if "AMD" in m.get("cpu", ""):
            zen4 = 0x10 <= mod <= 0x1F or 0x60 <= mod <= 0x7F or 0xA0 <= mod <= 0xAF
            gen = {23: "Zen/Zen 2", 25: "Zen 4" if zen4 else "Zen 3", 26: "Zen 5"}.get(fam, "")
    except ValueError:
        pass
    return (f"{m.get('cpu', '?')}, x86 family {m.get('family', '?')} model {m.get('model', '?')}"
            + (f" ({gen})" if gen else "") + f", L2 {m.get('l2', '?')} per core, "
            f"{m.get('vector') or 'no AVX'}, {m.get('mhz', '?')} MHz, {m.get('cpus', '?')} CPUs")


w = [max(len(r[i]) for r in rows + [("figure", "value", "target", "verdict")]) for i in range(4)]
line = "-+-".join("-" * x for x in w)
print("=" * len(line))
print(f"SUMMARY{' (QUICK mode: short runs, noisy)' if quick else ''}; p-st/s = particle-steps per second")
host = machine()
if host:
    print(f"machine: {host}")
print("=" * len(line))
for r in [("figure", "value", "target", "verdict")] + rows:
    print(" | ".join(c.ljust(x) for c, x in zip(r, w)))
    if r[0] == "figure":
        print(line)
met = sum(r[3] == "met" for r in rows)
missed = sum(r[3] == "NOT met" for r in rows)
print(f"targets met: {met}, not met: {missed}, not measured: "
      f"{sum(r[3] == 'not measured' for r in rows)}")

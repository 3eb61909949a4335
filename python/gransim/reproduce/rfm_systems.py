"""What the Random Force Model runs of a `gransim reproduce rfm` folder simulated, read from their
scene.toml files: each sweep's system for the report's introduction, and the facts (time step,
free-path box, the ring of G₁) that fill the departures table."""
import glob
import math
import os

from . import described
from .rfm_conditions import sweep_for


def _scenes(d, sweep):
    return described.scenes(sorted(os.path.dirname(p) for p in
                                   glob.glob(os.path.join(d, "sweeps", sweep, "*", "scene.toml"))))


def departure_facts(d):
    """the runs' own time step, free-path box, ring sizes and transient, from their scene.toml"""
    # the sweeps the free-path and G₁ claims read (the plan may give each its own)
    ref, struct, ring = (_scenes(d, s) for s in ("reference", sweep_for(d, "Df-freepath", "structure"),
                                                 sweep_for(d, "G1-bisection", "ring")))
    facts = {}

    def collect(scenes, get):
        out = []
        for s in scenes:
            try:
                v = get(s)
            except (KeyError, TypeError, ValueError, IndexError):
                continue
            if v not in out:
                out.append(v)
        return out

    facts["dt"] = collect(ref + struct + ring, lambda s: float(s["integrator"]["dt"]))
    facts["free_path_box"] = collect(struct, lambda s: float(s["box"]["width"]))
    facts["ring_n"] = collect(ring, lambda s: sum(int(x["count"]) for x in s["species"]))
    facts["discard"] = collect(ref, lambda s: float(s["rfm"]["discard_time"]))
    # the contact time π√(m₁₂/k_s) of the reference fluid's beads, in steps
    tc = collect(ref, lambda s: math.pi * math.sqrt(float(s["species"][0]["mass"]) / 2
                                                    / float(s["material"][0]["ks"])))
    if tc and len(facts["dt"]) == 1:
        facts["steps_per_contact"] = tc[0] / facts["dt"][0]
    return facts if any(facts.values()) else None


def system(d, sweep):
    """N, L, φ and ε of a sweep's runs, from their scene.toml ("" when the sweep has none)"""
    found = _scenes(d, sweep)
    ns, ls, phis, eps = [], [], [], []
    for s in found:
        try:
            sp = s["species"]
            n = sum(int(x.get("count", 0)) for x in sp)
            box = s["box"]
            e = float(s["material"][0].get("eps_n", float("nan")))
            if "reduced_length" in box:
                size = f"L′ = {float(box['reduced_length']):g} m"
                phi = None
            else:
                w, h = float(box["width"]), float(box.get("height", box["width"]))
                size = f"L = {w:g} m"
                phi = sum(int(x.get("count", 0)) * math.pi * float(x["radius"]) ** 2
                          for x in sp) / (w * h)
        except (KeyError, TypeError, ValueError, IndexError, ZeroDivisionError):
            continue
        for lst, v in ((ns, n), (ls, size), (phis, phi), (eps, e)):
            if v is not None and v not in lst:
                lst.append(v)
    if not ns:
        return ""
    out = "N = " + ", ".join(str(n) for n in sorted(ns)) + ", " + " or ".join(ls)
    if phis:
        out += ", φ = " + " or ".join(f"{p:.3g}" for p in phis)
    return out + ", ε = " + " or ".join(f"{e:g}" for e in eps)


# the sweeps a report can hold, named as its introduction names them
SYSTEMS = (("the 2D reference fluid", "reference"), ("the structure fluid", "structure"),
           ("the structure fluid of g(R) and the crossover", "structure_l04"),
           ("the free-path fluid", "freepath"), ("the fluids over φ", "moments_phi"),
           ("the 1D ring", "ring"), ("the 1D ring of G₁ and T(t)", "ring_n512"),
           ("the 1D rings over ε", "ring_eps"))

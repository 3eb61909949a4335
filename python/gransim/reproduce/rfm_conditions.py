"""The conditions under which the thesis makes each Random Force Model claim, and the check of a
sweep's runs against them from DIR/plan.json's sweeps[].conditions: a claim is judged only on
runs at the thesis' parameters and after the time the thesis shows is needed; otherwise it is
not resolved and says what is missing. A plan without conditions (older runs) skips the check,
and the claims keep their own checks of the runs (discarded transient, ring sizes, N)."""
import json
import math
import os

from . import described
from .verdicts import UNRESOLVED, Verdict

PHI_TOL = 5e-4  # the thesis prints φ to three decimals

# claim id -> the thesis' conditions: dim (2: periodic box, 1: ring), phi, phi_below, eps (ε_n,
# and ε_t in 2D), eps_below (1D), L (2D box side, m), L1 (ring's L′, m), N, sizes (distinct N
# ≥ N_from), starts, discard_s, sampled_s (the time the thesis shows is needed, or with
# sampled_as_run the time it sampled); 'source' quotes where each comes from
THESIS = {
    "T-start": dict(dim=2, phi=0.353, eps=0.6, L=0.2, N=2000, starts=2, discard_s=1.0,
                    source="§2.3.3: N = 2000, L = 0.2 m, ε = 0.6 from three starts (Fig. 2.10b), "
                           "steady after the first second"),
    "transient": dict(dim=2, phi=0.353, eps=0.6, L=0.2, N=2000,
                      source="§2.3.3, Fig. 2.10a: N = 2000, L = 0.2 m, ε = 0.6"),
    "T-mean-field": dict(dim=2, phi_below=0.1, discard_s=1.0,
                         source="§5.1: eq. 5.2 is derived for φ < 0.1"),
    "Df-Sk": dict(dim=2, phi=0.530, eps=0.1, L=0.2, discard_s=1.0,
                  source="Table 4.1: φ = 0.530, L = 0.2 m, ε = 0.1"),
    "Df-freepath": dict(dim=2, phi=0.530, eps=0.1, L=0.6, discard_s=1.0,
                        source="§4.3.3, eq. 4.25: L = 0.6 m, φ = 0.530, ε = 0.1"),
    "alpha-reference": dict(dim=2, phi=0.353, eps=0.6, L=0.2, discard_s=1.0,
                            source="Table 5.1 read at ε = 0.6: φ = 0.353, L = 0.2 m"),
    "alpha-structure": dict(dim=2, phi=0.530, eps=0.1, L=0.2, discard_s=1.0,
                            source="Table 5.2: φ = 0.530, L = 0.2 m, ε = 0.1"),
    "xi2": dict(dim=1, eps_below=0.5, L1=1.0, sizes=2, N_from=398, discard_s=20.0,
                sampled_s=200.0, source="§3.1.3: L′ = 1 m, ε ≤ 0.5, N ≥ 398, 20 s relaxation, "
                                        "then 10 × 20 s sampled (Fig. 2.8: ≈ 200 s to settle)"),
    "xi-m": dict(dim=1, eps_below=0.5, L1=1.0, sizes=2, N_from=398, discard_s=20.0,
                 sampled_s=1000.0, sampled_as_run=True, source="§3.2.1: L′ = 1 m, ε < 0.5, N ≥ 398, 20 s relaxation, "
                                          "then 50 × 20 s sampled"),
    "G1-bisection": dict(dim=1, eps=0.1, N=512, discard_s=20.0, sampled_s=200.0,
                         source="§3.4: N = 2⁹ at ε = 0.1 (Fig. 3.16), after the 20 s relaxation "
                                "and the ≈ 200 s the 1D temperature takes to settle (Fig. 2.8)"),
    "T-ring-settle": dict(dim=1, eps=0.1, L1=1.0, discard_s=20.0, sampled_s=200.0,
                          source="§2.2.3, Fig. 2.8: ε = 0.1, L′ = 1 m, ≈ 200 s (shown at N = 1585, "
                                 "taken for every size as the thesis does)"),
    "xi2-eps": dict(dim=1, L1=1.0, sizes=2, N_from=398, discard_s=20.0, sampled_s=200.0,
                    source="§3.1.2–3.1.3: L′ = 1 m, N ≥ 398, 20 s relaxation, then 10 × 20 s "
                           "sampled (Fig. 2.8: ≈ 200 s to settle)"),
    "collapse": dict(dim=1, L1=1.0, sizes=2, N_from=398, discard_s=20.0, sampled_s=200.0,
                     source="§3.1.3, Fig. 3.3: the runs of Fig. 3.2 (L′ = 1 m, N ≥ 398, "
                            "10 × 20 s sampled)"),
    "xi-m-elastic": dict(dim=1, eps=0.999, L1=1.0, sizes=2, N_from=398, discard_s=20.0,
                         sampled_s=1000.0, sampled_as_run=True,
                         source="§3.2.1, Fig. 3.4(a): ε = 0.999, L′ = 1 m, 20 s relaxation, then "
                                "50 × 20 s sampled"),
    "v-pdf": dict(dim=1, eps=0.1, L1=1.0, sizes=2, discard_s=20.0,
                  source="§3.2.3, Fig. 3.6: ε = 0.1, N = 100…1585, after the 20 s relaxation "
                         "(its sampled time unstated)"),
    "zeta-m": dict(dim=1, eps=0.1, L1=1.0, sizes=2, N_from=398, discard_s=20.0,
                   sampled_s=1000.0, sampled_as_run=True,
                   source="§3.3.1 and Table 3.1: ε = 0.1, L′ = 1 m, the velocity moments' runs "
                          "(20 s relaxation, then 50 × 20 s sampled)"),
    # the 2D fluid against φ and the auxiliary models
    "g-R": dict(dim=2, phi=0.530, eps=0.1, L=0.4, discard_s=1.0,
                source="Fig. 4.7: φ = 0.530, L = 0.4 m, ε = 0.1"),
    "moments-phi": dict(dim=2, phi_below=0.1, eps=0.1, discard_s=1.0,
                        source="§5.1, Fig. 5.2: ε = 0.1, eq. 5.3 for φ < 0.1"),
    "alpha-phi": dict(dim=2, eps=0.1, L=0.2, discard_s=1.0,
                      source="Tables 5.1–5.2: L = 0.2 m, ε = 0.1"),
    "crossover": dict(dim=2, phi=0.530, eps=0.1, L=0.4, discard_s=1.0,
                      source="Table 5.3 at ε = 0.1, read as §5.1.3's system: φ = 0.530, "
                             "L = 0.4 m, N = 12000 (Figs. 5.6–5.7, whose ε sets Fig. 5.14 repeats)"),
    "spm-alpha": dict(dim=2, phi=0.530, eps=0.1, L=0.2, discard_s=1.0,
                      source="eq. 5.29 on Table 4.1's D_f: φ = 0.530, L = 0.2 m, ε = 0.1"),
    "spm-pv": dict(dim=2, phi=0.530, eps=0.1, L=0.6, discard_s=1.0,
                   source="Fig. 5.10: L = 0.6 m, φ = 0.530 (N = 27000), ε = 0.1"),
}


def plan_conditions(d):
    """{sweep name: conditions} of DIR/plan.json; where the plan states none (a plan written
    before it recorded them), the conditions its runs' scene.toml files give; None when
    neither does"""
    try:
        with open(os.path.join(d, "plan.json")) as f:
            sweeps = json.load(f).get("sweeps", [])
    except (OSError, ValueError):
        return None
    out = {s["name"]: s["conditions"] for s in sweeps
           if isinstance(s, dict) and isinstance(s.get("conditions"), dict) and "name" in s}
    if out:
        return out
    for s in sweeps:
        c = _scene_conditions(os.path.join(d, "sweeps", s.get("name", "")))
        if isinstance(s, dict) and c:
            out[s["name"]] = c
    return out or None


def _scene_conditions(sweep_dir):
    """a sweep's conditions, as plan.json states them, from its runs' scene.toml files"""
    import glob
    runs = sorted(os.path.dirname(p) for p in glob.glob(os.path.join(sweep_dir, "*", "scene.toml")))
    points, seeds, starts, durations, discards, dims = [], [], [], [], [], []
    for s in described.scenes(runs):
        try:
            sp, box, mat = s["species"], s["box"], s["material"][0]
            n = sum(int(x.get("count", 0)) for x in sp)
            e_n = float(mat.get("eps_n", math.nan))
            e_t = float(mat.get("eps_t", 1.0))
            if "reduced_length" in box:
                lr = float(box["reduced_length"])
                d = sum(int(x.get("count", 0)) * 2 * float(x["radius"]) for x in sp)
                q = {"phi": d / (lr + d), "eps_n": e_n, "eps_t": 1.0, "reduced_length": lr, "N": n}
                dims.append(1)
            else:
                w, h = float(box["width"]), float(box.get("height", box["width"]))
                a = sum(int(x.get("count", 0)) * math.pi * float(x["radius"]) ** 2 for x in sp)
                q = {"phi": a / (w * h), "eps_n": e_n, "eps_t": e_t, "L": w, "N": n}
                dims.append(2)
            dur = float(s["scene"]["duration"])
            dis = float(s.get("rfm", {}).get("discard_time", 0.0))
        except (KeyError, TypeError, ValueError, IndexError, ZeroDivisionError):
            continue
        prep = s.get("preparation", {})
        for lst, v in ((points, q), (seeds, prep.get("seed")), (starts, prep.get("placement")),
                       (durations, dur), (discards, dis)):
            if v is not None and v not in lst:
                lst.append(v)
    if not points or len(set(dims)) != 1:
        return None
    # every run must reach the thesis' time: the shortest run and the longest discard decide
    dur, dis = min(durations), max(discards)
    return {"dimension": dims[0], "points": points, "seeds": seeds, "starts": starts,
            "duration_s": dur, "discard_s": dis, "sampled_s": dur - dis, "from_scenes": True}


def _fmt(x):
    return f"{x:.3g}" if isinstance(x, float) else str(x)


def _point_misses(t, c, q):
    """what a plan point q of a sweep with conditions c lacks of the thesis' conditions t, as
    (quantity, the point's value, the thesis') triples"""
    out = []
    dim = c.get("dimension")
    if t.get("dim") is not None and dim != t["dim"]:
        have = {1: "a 1D ring", 2: "a 2D fluid"}
        return [("", have.get(dim, f"dimension {dim}"), have[t["dim"]])]
    phi, n, e_n = q.get("phi", math.nan), q.get("N"), q.get("eps_n", math.nan)
    if "phi" in t and not abs(phi - t["phi"]) <= PHI_TOL:
        out.append(("φ", f"{phi:.3f}", f"{t['phi']:.3f}"))
    if "phi_below" in t and not phi < t["phi_below"]:
        out.append(("φ", f"{phi:.3f}", f"φ < {t['phi_below']:g}"))
    if "eps" in t:
        e = [e_n] + ([q.get("eps_t", math.nan)] if t["dim"] == 2 else [])
        if not all(abs(x - t["eps"]) <= 1e-9 for x in e):
            out.append(("ε", "/".join(f"{x:g}" for x in e), f"{t['eps']:g}"))
    if "eps_below" in t and not e_n <= t["eps_below"]:
        out.append(("ε", f"{e_n:g}", f"ε ≤ {t['eps_below']:g}"))
    for key, name, unit in (("L", "L", "L"), ("L1", "L′", "reduced_length")):
        if key in t and not abs(q.get(unit, math.nan) - t[key]) <= 1e-9 * t[key]:
            out.append((name, f"{q.get(unit, math.nan):g} m", f"{t[key]:g} m"))
    if "N" in t and n != t["N"]:
        out.append(("N", str(n), str(t["N"])))
    if "N_from" in t and not (n or 0) >= t["N_from"]:
        out.append(("N", str(n), f"N ≥ {t['N_from']}"))
    return out


def _phrases(per):
    """the misses of the points closest to the thesis', one phrase a quantity over its points"""
    fewest = min(len(m) for m in per)
    merged = {}
    for m in per:
        if len(m) == fewest:
            for name, have, want in m:
                haves = merged.setdefault((name, want), [])
                if have not in haves:
                    haves.append(have)
    return [f"{name + ' = ' if name else ''}{', '.join(h)} where the thesis has {want}"
            for (name, want), h in merged.items()]


def misses(cid, c):
    """what the runs of a sweep with plan conditions c lack of the thesis' conditions for claim
    cid, as phrases ("N = 4000 where the thesis has 512"); [] when they meet them"""
    t = THESIS.get(cid)
    if t is None:
        return []
    points = c.get("points") or []
    per = [_point_misses(t, c, q) for q in points]
    ok = [q for q, m in zip(points, per) if not m]
    out = []
    if not points:
        out.append("the plan lists no point")
    elif "sizes" in t:
        n = sorted({q.get("N") for q in ok})
        if len(n) < t["sizes"]:
            bad = [m for m in per if m]
            out.append(f"{len(n)} ring size(s) at the thesis' parameters where the fit needs "
                       f"{t['sizes']}" + (f" ({'; '.join(_phrases(bad))})" if bad else ""))
    elif not ok:
        out += _phrases(per)
    if "starts" in t and len(c.get("starts") or []) < t["starts"]:
        out.append(f"{len(c.get('starts') or [])} start(s) where the claim compares "
                   f"{t['starts']} at least")
    verb = "sampled" if t.get("sampled_as_run") else "needed"
    for key, what, need in (("discard_s", "discarded", "the thesis discards"),
                            ("sampled_s", "sampled", f"the thesis {verb}")):
        have = c.get(key)
        if key in t and not (isinstance(have, (int, float)) and have >= t[key] - 1e-6):
            out.append(f"{_fmt(have)} s {what} where {need} ≈ {t[key]:g} s")
    return out


def sweep_for(d, cid, default):
    """the sweep a claim reads: of those whose plan conditions list the claim, the first that
    meets the thesis' conditions, else the first other sweep that meets them (eq. 5.2's φ < 0.1
    in a sweep over φ), else the first listed; the default without plan conditions"""
    conds = plan_conditions(d)
    if not conds:
        return default
    listed = [n for n, c in conds.items() if cid in (c.get("claims") or [])]
    good = [n for n in listed if not misses(cid, conds[n])]
    good += [n for n, c in conds.items() if n not in listed and cid in THESIS and not misses(cid, c)]
    return (good or listed or [default])[0]


def gate(d, cid, sweep, v):
    """the verdict v, or not resolved with what the sweep's runs lack of the thesis' conditions
    (the verdict at face value kept in the reason); unchanged without plan conditions"""
    conds = plan_conditions(d)
    if conds is None or not sweep:  # no plan conditions, or a model run (no sweep) to check
        return v, ""
    c = conds.get(sweep)
    miss = ([f"the plan states no conditions for sweep {sweep}"] if c is None
            else misses(cid, c))
    if not miss:
        return v, ""
    what = "; ".join(miss)
    face = v.reason if v.verdict == UNRESOLVED else f"{v.verdict}, {v.reason}"
    return (Verdict(UNRESOLVED, f"not at the thesis' conditions ({THESIS[cid]['source']}): "
                    f"sweep {sweep} has {what}; at face value: {face}", v.null, v.alternative,
                    v.power, math.nan, v.power_at), what)

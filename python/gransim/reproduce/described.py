"""What a report says about the runs it has, read from them: the pile of a tapping study (grains
per species, box, integrator, pulse) from each run's scene.toml, and whether the plan that made
them resolves any claim (plan.json). A report never describes a pile or a budget it did not run."""
import json
import os

try:
    import tomllib
except ModuleNotFoundError:  # Python < 3.11
    tomllib = None


def plan(folder):
    """plan.json of a reproduction ({} when absent or unreadable)"""
    try:
        with open(os.path.join(folder, "plan.json")) as f:
            p = json.load(f)
        return p if isinstance(p, dict) else {}
    except (OSError, ValueError):
        return {}


def plan_resolves(p):
    """(resolves, why not): a plan says whether its runs can decide a claim; an older plan.json
    without the field says so in its purpose"""
    purpose = str(p.get("purpose", ""))
    resolves = p.get("resolves", "resolves no claim" not in purpose)
    return bool(resolves), purpose


def without_verdicts(claims, budget, purpose):
    """every claim 'not resolved', saying why: the plan's runs prove the pipeline only"""
    from .verdicts import UNRESOLVED
    why = (f"no verdict: the {budget} plan resolves no claim ({purpose}); its numbers show that "
           "the pipeline runs, not what the program does at the source's scale")
    for c in claims:
        c.reason = f"{why}. The test on these runs: {c.reason}" if c.reason else why
        c.verdict = UNRESOLVED
        if not c.resolve:
            c.resolve = "a budget whose plan resolves claims (quick or more)"
    return claims


def scenes(run_dirs):
    """the scene.toml of each run directory that has one, as dicts"""
    out = []
    for d in run_dirs:
        path = os.path.join(d, "scene.toml")
        if tomllib is None or not d or not os.path.exists(path):
            continue
        try:
            with open(path, "rb") as f:
                out.append(tomllib.load(f))
        except (OSError, ValueError):
            continue
    return out


def _g(x):
    return f"{x:g}"


def pile(scene_list):
    """the pile the runs tapped, in words and numbers: {"text", "grains", "box_width", "dt",
    "integrator"}; None without a scene. Runs that differ (a time-step check) list each value."""
    if not scene_list:
        return None

    def values(get):
        seen = []
        for s in scene_list:
            try:
                v = get(s)
            except (KeyError, TypeError, IndexError):
                continue
            if v not in seen:
                seen.append(v)
        return seen

    grains = values(lambda s: sum(int(sp.get("count", 0)) for sp in s["species"]))
    kinds = values(lambda s: tuple((sp.get("name", "?"), int(sp.get("count", 0)),
                                    float(sp.get("radius", 0.0)), int(sp.get("sides", 0)))
                                   for sp in s["species"]))
    width = values(lambda s: float(s["box"]["width"]))
    dt = values(lambda s: float(s["integrator"]["dt"]))
    integ = values(lambda s: str(s["integrator"]["kind"]).replace("_", " "))
    t1 = values(lambda s: float(s["drive"]["t1"]) if s["drive"]["kind"] == "negative_g"
                else None)
    t1 = [t for t in t1 if t is not None]
    quench = values(lambda s: bool(s["drive"].get("quench", False)))
    early = values(lambda s: bool(s["drive"].get("early_rest", False)))
    parts = []
    if grains:
        parts.append(" or ".join(str(n) for n in grains) + " grains")
    if kinds:
        parts.append("(" + "; ".join(", ".join(
            f"{n} {name} of radius {r * 1000:g} mm" + (f", {s} sides" if s else "")
            for name, n, r, s in k) for k in kinds) + ")")
    if width:
        parts.append("in a box " + " or ".join(f"{w:g} m" for w in width) + " wide")
    text = " ".join(parts)
    if integ or dt:
        steps = " or ".join(f"{d:.4g}" for d in dt)
        text += ", " + " or ".join(integ) + " at Δt = " + steps + " s"
    if t1:
        text += ", negative-g pulses of t1 = " + " or ".join(_g(t) for t in t1) + " s"
    if True in early:
        text += ", early rest" + (" with the quench" if True in quench else "")
    return {"text": text, "grains": grains, "box_width": width, "dt": dt, "integrator": integ,
            "t1": t1}

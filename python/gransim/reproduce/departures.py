"""Where each study's runs depart from what its source printed: the departures table at the top
of a report. Every row says what the source printed, what the program runs, why, and the
measured effect (one change at a time, standard errors with the integrated autocorrelation
time), or "not measured" where no run has measured it. The numbers are those of the
investigations in docs/reproduction/README.md and docs/tapping.md; the reasons are argued in
docs/physics.md, which each row links (relative to the published report, docs/reproduction/X/)."""

PHYSICS = "../../physics.md"
README = "../README.md"
TAPPING = "../../tapping.md"

# (departure, source printed, program runs, why, [link text, target], measured effect)
TAPPING_ROWS = [
    ("pulse of negative g",
     "g = 9.81 m/s²·g_p for t1 = 0.1 s every T = 3 s (P.37)",
     "g_p·g for t1 = 0.01 s (same g_p values)",
     "as printed, g_p = 6 launches the pile 2 m high and above g_p = 14 the flight outlasts "
     "T = 3 s, while the paper rests the pile before every pulse; its Fig. 4 caption's "
     "\"g_p g = 6 m/s²\" fits g_p m/s² for 0.1 s, which has the same take-off speed as g_p·g "
     "for 0.01 s", ("physics.md §8.8", PHYSICS + "#88-pulse-length-of-negative-g"),
     "as printed: not measured (cannot rest between pulses above g_p = 14). Read as g_p m/s² "
     "for 0.1 s: −0.0056 ± 0.0007 at g_p = 6 (8σ), +0.0018 ± 0.0006 at g_p = 20 (50 taps "
     "each)"),
    ("box width",
     "280 mm", "0.48 m",
     "1184 grains cover 0.2056 m²: a 280 mm box holds a pile ≈ 900 mm tall that fills the "
     "rotating-g box and cannot hold the printed 400 mm test square; 480 mm makes the three "
     "sizes consistent", ("physics.md §8.1", PHYSICS + "#81-box-width-of-the-paper"),
     "280 mm: not measured (not a consistent scene). 0.56 m with 7/6 of the grains (the pile "
     "as deep, the square centred): +0.0041 ± 0.0007 at g_p = 6 (5.7σ)"),
    ("end of a relaxation",
     "a fixed period T = 3 s (residual motion below 10⁻⁵ in φ)",
     "early rest with the quench: the relaxation ends once every grain is slower than 1 mm/s; "
     "velocities are zeroed at kinetic-energy peaks once every grain has been below 5 cm/s "
     "for 0.3 s",
     "the pile rings elastically through the whole period, so it never meets a rest "
     "criterion by itself; the contacts that decide φ are fixed before the quench acts",
     ("physics.md §2.4", PHYSICS + "#24-box-preparation-and-tapping-protocols"),
     "fixed 3 s periods: +0.0004 ± 0.0006 at g_p = 6 (0.7σ, 42 taps); −0.0006 ± 0.0009 "
     "(0.6σ, 60 taps) at paper scale with Δt = 10⁻⁴ s (docs/tapping.md)"),
    ("rocking damping",
     "the normal dashpot acts on ḣ_eff only (P.34)",
     "the dashpot spread along the contact line (`model.rocking_damping`)",
     "a grain rocking on a face keeps its overlap area, so the printed dashpot leaves that "
     "mode undamped: a tilted decagon rocks forever and piles never come to rest",
     ("physics.md §2.2", PHYSICS + "#22-force-law-polygons"),
     "the paper's dashpot: +0.0004 ± 0.0007 at g_p = 6 (0.5σ); +0.0011 ± 0.0008 at "
     "f = 2 Hz (1.4σ)"),
    ("integrator",
     "sixth-order Gear predictor–corrector, Δt = 5·10⁻⁵ s",
     "velocity Verlet, Δt = 1/7500 s (0.19 contact times)",
     "Gear 6 at the paper's step sits at the edge of its stability on a small grain's contacts "
     "and the pile never comes to rest (grains at 0.2–0.8 m/s at the measurements); velocity "
     "Verlet is stable there and lets the relaxation end at rest",
     ("physics.md §2.3", PHYSICS + "#23-integrators"),
     "Gear 6 at 5·10⁻⁵ s: +0.0053 ± 0.0011 at g_p = 6 (4.8σ, σ_φ × 2.8: a pile still in "
     "motion). Velocity Verlet at Δt = 10⁻⁴ s: +0.0000 ± 0.0008"),
    ("sign of the normal dashpot",
     "F⊥ = max(E h_eff − γ√(E m⊥) ḣ_eff, 0) (P.34)",
     "+γ√(E m⊥) ḣ_eff: repulsion while the grains approach",
     "the printed sign injects energy at every contact",
     ("physics.md §8.2", PHYSICS + "#82-sign-of-the-normal-dashpot-p34"),
     "not measured (the printed sign heats the pile: it never settles)"),
    ("rotation window of rotating g",
     "t̃ < ω/2π (P.38)", "t̃ < 2π/ω = 1/f: one full turn",
     "the paper's own period T = 2π/ω + 3 s", ("physics.md §8.3",
                                               PHYSICS + "#83-rotation-window-of-rotating-g-p38"),
     "not measured (as printed the window is not a turn)"),
]

RFM_ROWS = [
    ("bead mass",
     "M = 3.53·10⁵ kg (§2.3.2)", "3.53·10⁻⁵ kg",
     "a glass bead of r = 1.5 mm, as the thesis' Table 2.2 gives",
     ("physics.md §8.4", PHYSICS + "#84-mass-of-the-thesiss-beads"),
     "not measured (a misprint)"),
    ("time step",
     "Δt ≤ 2π√(M/k_s)", "Δt = 10⁻⁶ s (≈ 19 steps a contact)",
     "the printed rule allows steps longer than a contact; the intended one is about a tenth of "
     "the contact time π√(m₁₂/k_s) = 1.87·10⁻⁵ s",
     ("physics.md §8.6", PHYSICS + "#86-time-step-rule-of-the-thesis"), "not measured"),
    ("temperature of the reference fluid",
     "T ≈ 12 m²/s² (§2.3.3)", "not used as a target",
     "the energy balance of injection and dissipation gives 0.1–0.3 m²/s²",
     ("physics.md §8.5", PHYSICS + "#85-temperature-of-the-thesiss-reference-run"),
     "the reference runs measure ⟨T⟩ ≈ 0.24 m²/s²"),
    ("normal random numbers",
     "Box–Muller", "ziggurat normals from counter-based per-particle streams",
     "the same normal distribution, reproducible whatever the threads",
     ("physics.md §9", PHYSICS + "#9-choices-where-the-sources-are-silent"), "not measured"),
    ("drift of the 2D fluid",
     "not stated", "centre-of-mass velocity removed every 100 steps",
     "the kicks make the fluid's centre of mass walk at random; the thesis symmetrises the "
     "kicks of the ring (T.2.18) and states nothing for the 2D fluid",
     ("physics.md §9", PHYSICS + "#9-choices-where-the-sources-are-silent"), "not measured"),
    ("box of the free-path dimension",
     "L = 0.6 m (N = 27 000) over long runs (§4.3.3)", "L = 0.2 m (the reference scene's box)",
     "every budget runs the reference fluid in one box, the one its other claims use",
     ("the RFM investigation", README + "#the-random-force-model-at-the-quick-budget"),
     "not measured"),
    ("ring of the gap distribution G₁",
     "N = 512 (Fig. 3.16)", "the largest ring of the size series (N = 4000 below the full "
     "budget)", "the claim takes the ring with the most gaps of the size series that ξ₂ needs",
     ("docs/rfm.md, Evidence", "../../rfm.md#evidence"),
     "not measured as a KS distance; a 25 s ring of N = 512 follows the n = 9 bisection density "
     "over ten decades of G₁ (docs/rfm.md)"),
]

HEAD = ("The runs depart from what the source printed where the printed value cannot be run "
        "as it stands or where the program needs a choice the source does not make. Effects "
        "are the difference made by the source's choice, one change at a time")


def _or(values, fmt):
    return " or ".join(fmt(v) for v in values)


def rows(study, facts=None):
    """the study's rows; facts (what the runs' scene.toml give: tapping.departure_facts,
    rfm.departure_facts) put the runs' own values in the 'program runs' cells"""
    base = TAPPING_ROWS if study == "tapping" else RFM_ROWS
    if not facts:
        return base
    if study == "tapping":
        runs = {"box width": (facts.get("box_width"), lambda v: _or(v, lambda w: f"{w:g} m")),
                "integrator": (facts.get("dt"), lambda v: " or ".join(facts["integrator"]) +
                               ", Δt = " + _or(v, lambda d: f"{d:.4g} s")),
                "pulse of negative g": (facts.get("t1"), lambda v: "g_p·g for t1 = " +
                                        _or(v, lambda t: f"{t:g}") + " s (same g_p values)")}
    else:
        # rows that vanish when every run has the thesis' value: no departure to report
        if facts.get("free_path_box") and all(abs(w - 0.6) < 1e-9 for w in facts["free_path_box"]):
            base = [r for r in base if r[0] != "box of the free-path dimension"]
        if facts.get("ring_n") == [512]:
            base = [r for r in base if r[0] != "ring of the gap distribution G₁"]
        runs = {"time step": (facts.get("dt"), lambda v: "Δt = " + _or(v, lambda d: f"{d:g}") +
                              " s" + (f" (≈ {facts['steps_per_contact']:.0f} steps a contact)"
                                      if facts.get("steps_per_contact") else "")),
                "box of the free-path dimension": (facts.get("free_path_box"), lambda v: "L = " +
                                                   _or(v, lambda w: f"{w:g}") + " m (the box of "
                                                   "the runs that measure it)"),
                "ring of the gap distribution G₁": (
                    facts.get("ring_n"),
                    lambda v: f"the largest ring of these runs' size series (N = {max(v)})")}
    out = []
    for r in base:
        values, cell = runs.get(r[0], (None, None))
        out.append((r[0], r[1], cell(values)) + r[3:] if values else r)
    return out


def head(study, facts=None):
    text = HEAD + (" (φ̄ with it − φ̄ as run, ± one standard error):" if study == "tapping" else
                   ", on what the claims measure:")
    if study == "tapping" and facts and facts.get("grains") and facts["grains"] != [1184]:
        n = " or ".join(str(g) for g in facts["grains"])
        text = (f"These runs tap a pile of {n} grains, not the paper's 1184: the effects below "
                "were measured on the paper-scale scenes, and the 'program runs' cells give "
                "these runs' own box and time step. " + text)
    return text

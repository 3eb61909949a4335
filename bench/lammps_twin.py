#!/usr/bin/env python3
"""The settled-pile twin: one packed configuration for gransim and LAMMPS, and the parameter map.

usage: lammps_twin.py SCENE OUTDIR
  SCENE   scenes/bench_settled_10k.toml (one disk species, Model S, walls, gravity)
  OUTDIR  gets scene.toml (SCENE + the crystal as [[preparation.particle]] entries) and
          settled.data (the same crystal, LAMMPS atom_style sphere)
Prints the LAMMPS `-var name value` arguments for bench/lammps/settled.in on stdout.

The crystal: rows of touching disks (spacing d = 2r) stacked at d·√3/2, even rows from the left
wall, odd rows against the right wall (box width = (n_x + ½)·d), the bottom row on the floor; so
every disk touches its six neighbours (or a wall) from the first step and the pile only has to
take up its weight (overlaps of ~10⁻⁸ m). Both codes start from it at rest.

Parameter map (gransim Model S, src/force/laws/disk_law.hpp ↔ LAMMPS gran/hooke/history):
  k_n = k_s;  k_t = 10⁻⁶·k_s: gransim has no tangential spring, but LAMMPS's history update
  divides by k_t when a contact slides (k_t = 0 gives NaN at the first sliding contact); the
  spring then adds ~10⁻⁶ of the normal force scale;
  γ_n(LAMMPS, 1/s) = g_n/m₁₂ with g_n = gransim's dashpot for ε_n (T.2.6);
  γ_t(LAMMPS, 1/s) = g_t/m₁₂ with g_t = −√(k_s m₁₂)/π·ln ε_t (T.2.12);
  m₁₂ = m/2 between disks, m against a wall (LAMMPS: the same reduced masses), so the walls
  (fix wall/gran) get their own γ_n, γ_t: those of the pair divided by √2;
  xmu = μ (both cap |F_t| at μ·F_n); dampflag 1.
"""
import math
import sys
import tomllib


def gamma_normal(eps, m12, ks):  # kg/s, as law::gamma_normal
    if eps >= 1.0:
        return 0.0
    a = math.log(eps) / math.pi
    return math.sqrt(a * a * 4.0 * m12 * ks / (1.0 + a * a))


def gamma_tangential(eps_t, m12, ks):  # kg/s, as law::gamma_tangential
    return 0.0 if eps_t >= 1.0 else -math.sqrt(ks * m12) / math.pi * math.log(eps_t)


def main():
    scene_path, out = sys.argv[1], sys.argv[2]
    with open(scene_path, "rb") as fh:
        sc = tomllib.load(fh)
    sp = sc["species"][0]
    mat = sc["material"][0]
    r, m, n = sp["radius"], sp["mass"], sp["count"]
    d = 2 * r
    width, height = sc["box"]["width"], sc["box"]["height"]
    nx = round(width / d - 0.5)
    ny = math.ceil(n / nx)
    dy = d * math.sqrt(3.0) / 2.0
    if ny * dy + d > height:
        sys.exit(f"lammps_twin: {n} disks in {ny} rows do not fit under height {height}")
    pts = []
    for j in range(ny):
        for i in range(nx):
            if len(pts) < n:
                pts.append((r + i * d + (r if j % 2 else 0.0), r + j * dy))

    # gransim: the scene plus explicit particles ([preparation] is the scene file's last table)
    with open(scene_path) as fh:
        text = fh.read()
    with open(f"{out}/scene.toml", "w") as fh:
        fh.write(text)
        for x, y in pts:
            fh.write(f"\n[[preparation.particle]]\nx = {x!r}\ny = {y!r}\n")

    # LAMMPS: atom_style sphere, "id type diameter density x y z"; the mass is set in settled.in
    with open(f"{out}/settled.data", "w") as fh:
        fh.write(f"gransim bench crystal from {scene_path}\n\n{len(pts)} atoms\n1 atom types\n\n")
        fh.write(f"0 {width!r} xlo xhi\n0 {height!r} ylo yhi\n{-r!r} {r!r} zlo zhi\n\nAtoms # sphere\n\n")
        for k, (x, y) in enumerate(pts, 1):
            fh.write(f"{k} 1 {d!r} 1.0 {x!r} {y!r} 0.0\n")

    ks, en, et, mu = mat["ks"], mat["eps_n"], mat["eps_t"], mat["mu"]
    m_pair, m_wall = m / 2.0, m
    v = {
        "nsteps": None, "kn": ks, "kt": 1e-6 * ks, "mass": m, "dt": sc["integrator"]["dt"], "g": sc["drive"]["g"],
        "xmu": mu if mu > 0 else 1e4,  # gransim μ = 0 means no cap
        "gn": gamma_normal(en, m_pair, ks) / m_pair, "gt": gamma_tangential(et, m_pair, ks) / m_pair,
        "gnw": gamma_normal(en, m_wall, ks) / m_wall, "gtw": gamma_tangential(et, m_wall, ks) / m_wall,
        "width": width, "skin": 0.1 * d,
    }
    print(" ".join(f"-var {k} {val:.10g}" for k, val in v.items() if val is not None))


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Copy a scene with a saved state as its start: usage scene_from_state.py SCENE STATE OUT.

STATE is a gransim state file (`# gransim state v1`, columns id,species,x,y,theta,vx,vy,omega,
as `gransim run` writes to state.csv); its grains become [[preparation.particle]] entries
appended to the copy (valid TOML after any table) and preparation.settle_time is set to 0 with
`--set` by the caller. The benchmark uses it to tap the settled paper pile
(bench/data/paper_pile_settled.csv) without paying the 3 s of settling every run.
"""
import csv
import sys


def main():
    scene, state, out = sys.argv[1:4]
    with open(state) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    with open(scene) as fh:
        text = fh.read()
    with open(out, "w") as fh:
        fh.write(text)
        for r in rows:
            fh.write(f'\n[[preparation.particle]]\nspecies = "{r["species"]}"\n')
            for k in ("x", "y", "theta", "vx", "vy", "omega"):
                fh.write(f"{k} = {float(r[k])!r}\n")


if __name__ == "__main__":
    main()

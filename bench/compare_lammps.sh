#!/usr/bin/env bash
# gransim against LAMMPS (Debian's `lammps`, gran/hooke/history) on two 10⁴-disk scenes:
#   fluid    the randomly forced periodic fluid (scenes/bench_fluid_10k.toml ↔ bench/lammps/forced_fluid.in)
#   settled  disks resting under gravity in a walled box (scenes/bench_settled_10k.toml ↔
#            bench/lammps/settled.in), both started at rest from the same packed crystal
#            (bench/lammps_twin.py writes the gransim scene with it, the LAMMPS data file and the
#            LAMMPS parameters)
# Prints particle-steps per second (LAMMPS: its "Loop time"; gransim: run.json, the stepping) for
# 1 and 2 threads (gransim, OpenMP) / ranks (LAMMPS, MPI) and the ratios (one core: the median of
# three runs of each code, taken in turn), and the per-core ratio once more with both codes
# running at the same time on the two CPUs (paired); nothing is asserted.
# Environment: STEPS (default 10000; QUICK=1: 2000), GS_BUILD_DIR (default build),
# GS_BENCH_RESULTS (file to append "key value" lines to, for bench/summary.py),
# OMP_WAIT_POLICY (default: the runtime's), GS_MPI_ARGS (default "--mca mpi_yield_when_idle 1").
set -euo pipefail
cd "$(dirname "$0")/.."
. bench/common.sh  # OMP_WAIT_POLICY, mpi_args, root, gs
steps=${STEPS:-$([ "${QUICK:-0}" = 1 ] && echo 2000 || echo 10000)}
results=${GS_BENCH_RESULTS:-/dev/null}
if ! command -v lmp >/dev/null; then
  sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd=sudo
  $sudo_cmd apt-get update -q && DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends lammps
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mpi=1
command -v mpirun >/dev/null || { mpi=0; echo "mpirun missing: LAMMPS on 2 ranks skipped"; }

# the settled pile: scene with the crystal, data file and LAMMPS variables
python3 bench/lammps_twin.py scenes/bench_settled_10k.toml "$tmp" >"$tmp/settled.vars"

num() { sed 's/.*: *//; s/,.*//'; }
# the median of its arguments (numbers; nan sorts last)
median() {
  python3 -c "import sys
v = sorted(map(float, sys.argv[1:]), key=lambda x: (x != x, x))
print(v[(len(v) - 1) // 2])" "$@"
}

# gransim SCENE_FILE DT THREADS: particle-steps/s of `steps` steps
gransim() {
  local dur out=$tmp/g$3
  dur=$(python3 -c "print($steps*$2)")
  OMP_NUM_THREADS=$3 "$gs" run "$1" --out "$out" --force --quiet --set scene.duration="$dur" \
    --set output.final_state=true 2>/dev/null
  grep '"particle_steps_per_s"' "$out/run.json" | num
}

# lammps INPUT RANKS N VARS...: particle-steps/s of `steps` steps (Loop time)
lammps() {
  local in=$1 ranks=$2 n=$3 out
  shift 3
  if [ "$ranks" -eq 1 ]; then
    out=$(cd "$tmp" && lmp -in "$in" -var nsteps "$steps" "$@" -log none)
  else
    out=$(cd "$tmp" && mpirun --allow-run-as-root --oversubscribe "${mpi_args[@]}" -np "$ranks" lmp -in "$in" \
      -var nsteps "$steps" "$@" -log none)
  fi
  echo "$out" >"$tmp/lammps$ranks.out"
  local loop
  loop=$(echo "$out" | awk '/^Loop time/ {print $4}')
  if [ -z "$loop" ]; then  # LAMMPS stopped (an error): say so, keep the harness going
    echo "LAMMPS $in on $ranks rank(s) failed: $(echo "$out" | grep -m1 ERROR)" >&2
    echo nan
    return 0
  fi
  python3 -c "print($steps*$n/$loop)"
}

# paired FILE IN VARS...: per core with the two CPUs' speeds cancelled. Some hosts' vCPUs run
# at different speeds, and a vCPU's speed drifts by tens of per cent between minutes
# (docs/threads.md): gransim (1 thread) and LAMMPS (1 rank) run at the same time, one pinned to
# each of CPUs 0 and 1, then swapped; the ratio is the geometric mean of the two rounds'
# ratios. Prints "ratio g@0 g@1 l@0 l@1" (particle-steps/s).
paired() {
  local file=$1 in=$2
  shift 2
  local -A v=()
  local round gc lc
  for round in 0 1; do
    gc=$round; lc=$((1 - round))
    ( OMP_NUM_THREADS=1 taskset -c "$gc" "$gs" run "$file" --out "$tmp/p$round" --force --quiet \
        --set scene.duration="$(python3 -c "print($steps*1e-6)")" --set output.final_state=false \
        2>/dev/null; grep '"particle_steps_per_s"' "$tmp/p$round/run.json" | num >"$tmp/pg$round" ) &
    ( cd "$tmp" && taskset -c "$lc" lmp -in "$in" -var nsteps "$steps" "$@" -log none \
        | awk -v n=10000 -v s="$steps" '/^Loop time/ {print s*n/$4}' >"$tmp/pl$round" ) &
    wait
    v[g$gc]=$(cat "$tmp/pg$round"); v[l$lc]=$(cat "$tmp/pl$round")
  done
  python3 -c "
g0, g1, l0, l1 = (float(x or 'nan') for x in '${v[g0]} ${v[g1]} ${v[l0]} ${v[l1]}'.split(' '))
print(((g0 / l1) * (g1 / l0)) ** 0.5, g0, g1, l0, l1)"
}

# the settled pile after the run, both codes: mean height and kinetic energy (a sanity check
# that the twins do the same thing; they agree to a few per cent, not bitwise)
settled_check() {
  python3 - "$tmp/g1/state.csv" "$tmp/lammps1.out" <<'EOF'
import csv, sys
rows = list(csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith('#')))
m = 3.53e-5
ym = sum(float(r['y']) for r in rows) / len(rows)
ke = sum(0.5 * m * (float(r['vx'])**2 + float(r['vy'])**2) for r in rows)
lines = open(sys.argv[2]).read().splitlines()
i = [k for k, l in enumerate(lines) if l.split()[:1] == ['Step']][0]
_, lke, lym, _ = lines[i + 2].split()
y0 = 0.130104772462  # mean height of the crystal at the start
print(f"  check after the run: sink of the mean height gransim {y0-ym:.3g} m, LAMMPS "
      f"{y0-float(lym):.3g} m; kinetic energy gransim {ke:.3g} J, LAMMPS {float(lke):.3g} J")
EOF
}

printf '%-46s %16s\n' "10^4 disks, $steps steps of 1e-6 s" "particle-steps/s"
for scene in settled fluid; do
  if [ "$scene" = settled ]; then
    file=$tmp/scene.toml; in=$root/bench/lammps/settled.in
    read -r -a vars <"$tmp/settled.vars"; vars+=(-var data "$tmp/settled.data")
  else
    file=$root/scenes/bench_fluid_10k.toml; in=$root/bench/lammps/forced_fluid.in; vars=()
  fi
  declare -A r=()
  # one core: gransim and LAMMPS one after the other, three times in turn, and the median of
  # each, so that a slow spell of the host (minutes) falls on both codes alike
  g_runs=(); l_runs=()
  for rep in 1 2 3; do
    g_runs+=("$(gransim "$file" 1e-6 1)")
    l_runs+=("$(lammps "$in" 1 10000 "${vars[@]}")")
  done
  r[g1]=$(median "${g_runs[@]}"); r[l1]=$(median "${l_runs[@]}")
  printf '%-46s %16.4g  (median of %s)\n' "$scene: gransim (1 thread)" "${r[g1]}" "${g_runs[*]}"
  printf '%-46s %16.4g  (median of %s)\n' "$scene: LAMMPS gran/hooke/history (1 rank)" "${r[l1]}" \
    "${l_runs[*]}"
  r[g2]=$(gransim "$file" 1e-6 2)
  printf '%-46s %16.4g\n' "$scene: gransim (2 threads)" "${r[g2]}"
  if [ "$mpi" = 0 ]; then
    r[l2]=""
  else
    r[l2]=$(lammps "$in" 2 10000 "${vars[@]}")
    printf '%-46s %16.4g\n' "$scene: LAMMPS gran/hooke/history (2 ranks)" "${r[l2]}"
  fi
  [ "$scene" = settled ] && { settled_check || true; }
  r[pair]=nan
  if [ "$(nproc)" -ge 2 ] && command -v taskset >/dev/null; then
    read -r r[pair] g0 g1 l0 l1 < <(paired "$file" "$in" "${vars[@]}")
    printf '  %s, paired (at the same time, CPUs swapped): gransim %.4g / %.4g, LAMMPS %.4g / %.4g on CPU 0 / 1\n' \
      "$scene" "$g0" "$g1" "$l0" "$l1"
  fi
  python3 - "$scene" "${r[g1]}" "${r[g2]}" "${r[l1]}" "${r[l2]:-nan}" "${r[pair]}" "$results" <<'EOF'
import sys
s, (g1, g2, l1, l2, pr), res = sys.argv[1], map(float, sys.argv[2:7]), sys.argv[7]
print(f"  {s}: ratio gransim/LAMMPS per core {g1/l1:.2f} (one after the other), "
      f"{pr:.2f} (paired), on 2 cores {g2/l2:.2f}")
with open(res, "a") as fh:
    for k, v in (("gransim1", g1), ("gransim2", g2), ("lammps1", l1), ("lammps2", l2),
                 ("paired", pr)):
        fh.write(f"lammps.{s}.{k} {v:.6g}\n")
EOF
done

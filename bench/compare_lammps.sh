#!/usr/bin/env bash
# gransim against LAMMPS (Debian's `lammps`, gran/hooke/history) on the same 10⁴-disk randomly
# forced periodic fluid (scenes/bench_fluid_10k.toml ↔ bench/lammps/forced_fluid.in).
# Prints particle-steps per second for each and the ratio, with 1 and 2 threads/ranks.
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${STEPS:-10000}
if ! command -v lmp >/dev/null; then
  sudo_cmd=""; [ "$(id -u)" -ne 0 ] && sudo_cmd=sudo
  $sudo_cmd apt-get update -q && DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends lammps
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dt=1e-6
dur=$(python3 -c "print($steps*$dt)")
printf '%-34s %14s\n' "code (10^4 forced disks, $steps steps)" "particle-steps/s"
for threads in 1 2; do
  OMP_NUM_THREADS=$threads build/gransim run scenes/bench_fluid_10k.toml --out "$tmp/g$threads" \
    --force --quiet --set scene.duration="$dur" 2>/dev/null
  g=$(grep particle_steps_per_s "$tmp/g$threads/run.json" | tr -dc '0-9.e+-')
  printf '%-34s %14.4g\n' "gransim ($threads thread)" "$g"
  eval "g$threads=$g"
done
for ranks in 1 2; do
  if [ "$ranks" -eq 1 ]; then
    out=$(cd "$tmp" && lmp -in "$OLDPWD/bench/lammps/forced_fluid.in" -var nsteps "$steps" -log none)
  else
    command -v mpirun >/dev/null || { echo "mpirun missing: skipping 2 ranks"; continue; }
    out=$(cd "$tmp" && mpirun --allow-run-as-root --oversubscribe -np 2 lmp -in "$OLDPWD/bench/lammps/forced_fluid.in" -var nsteps "$steps" -log none)
  fi
  loop=$(echo "$out" | awk '/^Loop time/ {print $4}')
  l=$(python3 -c "print($steps*10000/$loop)")
  printf '%-34s %14.4g\n' "LAMMPS gran/hooke/history ($ranks rank)" "$l"
  eval "l$ranks=$l"
done
python3 -c "print('ratio gransim/LAMMPS per core: %.2f; on 2 cores: %.2f' % ($g1/$l1, $g2/${l2:-$l1}))"

#!/usr/bin/env bash
# Hash what every scene in scenes/ writes over a short run, with 1 and 2 threads and, for two
# scenes, under every integrator: two builds that must give the same results (a refactor, a
# compiler flag) print the same lines.
#   tools/scene_hashes.sh GRANSIM_BINARY > hashes.txt
# Each scene runs shortened (a few hundred steps, or two short taps after a short settle), so
# the whole list takes a few minutes; the lines are "scene threads variant file sha256".
set -euo pipefail
bin=$(realpath "$1")
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
shorten() {  # the overrides that make SCENE a short run exercising the same code
  case $(sed -n '/^\[drive\]/,/^\[/p' "$1" | grep -m1 '^kind' | cut -d'"' -f2) in
    negative_g)
      echo "--set preparation.settle_time=0.3 --set drive.taps=2 --set drive.period=0.3" ;;
    rotating_g)
      echo "--set preparation.settle_time=0.3 --set drive.taps=2 --set drive.f=5 --set drive.relax=0.1" ;;
    *) echo "--set scene.duration=$(awk '/^dt/ {print 300 * $3; exit}' "$1")" ;;
  esac
}
run_one() {  # SCENE THREADS VARIANT [OVERRIDES...]
  local scene=$1 threads=$2 variant=$3
  shift 3
  local out=$work/$(basename "$scene" .toml)-$threads-$variant
  if ! OMP_NUM_THREADS=$threads "$bin" run "$scene" -q -o "$out" $(shorten "$scene") "$@" \
    >"$out.log" 2>&1; then
    echo "$(basename "$scene") $threads $variant (run failed: $(tail -1 "$out.log"))"
    return
  fi
  (cd "$out" && find . -type f ! -name 'run.json' ! -name '*.gsck' ! -name '*.log' ! -name 'progress*' \
    ! -name '*.lock' | LC_ALL=C sort | while read -r f; do
      echo "$(basename "$scene") $threads $variant $f $(sha256sum <"$f" | cut -c1-16)"
    done)
}
for scene in scenes/*.toml; do
  for threads in 1 2; do run_one "$scene" "$threads" scene; done
done
for scene in scenes/collision_decagons.toml scenes/bench_fluid_10k.toml; do
  for kind in velocity_verlet gear6 position_verlet semi_implicit_euler; do
    for threads in 1 2; do run_one "$scene" "$threads" "$kind" --set integrator.kind=$kind; done
  done
done

#!/usr/bin/env bash
# The benchmark harness: build Release (tools/setup.sh), run the Google Benchmark kernels and
# whole steps, the cost-per-particle-step scan over N, gransim against LAMMPS, the tapping
# figures and the MPI sweep, then print one summary table with the targets. Nothing is asserted.
#
#   bench/run.sh            full run (≈ 10–15 minutes on an idle 2-core machine, after the build)
#   QUICK=1 bench/run.sh    short version (≈ 3 minutes): short benchmark times, 2000 LAMMPS
#                           steps, paper taps of 0.3 s (per-tap time extrapolated), no early-rest
#                           paper taps, 1 tap per small-pile run
# Environment: GS_BUILD_DIR (build directory, default build), GS_JOBS (build jobs),
#   GS_SKIP_BUILD=1 (use the binaries as they are),
#   GS_BENCH_OUT (keep the raw results here; default a temporary directory),
#   OMP_WAIT_POLICY (default: the runtime's; `passive` on a machine busy with other jobs, where
#   spinning threads stall each other), GS_MPI_ARGS (extra mpirun options, default
#   "--mca mpi_yield_when_idle 1"), STEPS (LAMMPS comparison steps).
set -euo pipefail
cd "$(dirname "$0")/.."
export GS_BUILD_DIR=${GS_BUILD_DIR:-build}
# the spin gransim gives its OpenMP threads (src/main.cpp), for gransim_bench too
[ -n "${OMP_WAIT_POLICY:-}" ] || export GOMP_SPINCOUNT=${GOMP_SPINCOUNT:-10000000}
quick=${QUICK:-0}
bin=$GS_BUILD_DIR/gransim_bench
t_start=$(date +%s)

[ "${GS_SKIP_BUILD:-0}" = 1 ] || GS_CMAKE_ARGS="-DGS_BUILD_BENCH=ON" tools/setup.sh all >/dev/null
if [ -n "${GS_BENCH_OUT:-}" ]; then out=$GS_BENCH_OUT; mkdir -p "$out"; rm -f "$out"/gb_*.json "$out/results.txt"
else out=$(mktemp -d); trap 'rm -rf "$out"' EXIT; fi
export GS_BENCH_RESULTS=$out/results.txt
: >"$GS_BENCH_RESULTS"
# the machine: the targets are absolute speeds, and VMs of one kind land on different CPUs
# (one CPU generation can run the pile at half another's speed: docs/benchmarks.md)
bench/machine.sh >"$out/machine.txt" || true

if [ "$quick" = 1 ]; then mt=0.1; mt_scan=0.2; else mt=1; mt_scan=1; fi
gbench() {  # JSON FILTER THREADS MIN_TIME: console table to stdout, JSON to $out
  OMP_NUM_THREADS=$3 ${pin_cmd:-} "$bin" --benchmark_min_time="$4" --benchmark_filter="$2" ${gb_extra:-} \
    --benchmark_out="$out/$1" --benchmark_out_format=json 2>/dev/null || echo "($1: gransim_bench failed)"
}
echo "== kernels and whole steps (Google Benchmark; 1 thread) =="
gbench gb_1t.json 'Decagon|AreaInRect|Pile|Disk|Render|Frame|Png|Rfm2D|RingNeighbours' 1 "$mt"
echo "== the 1D ring, five times interleaved (its target is a 1-thread figure) =="
gb_extra="--benchmark_repetitions=5 --benchmark_enable_random_interleaving=true" \
  gbench gb_ring.json 'Rfm1DRing' 1 "$mt"
echo "== the same whole steps with 2 threads =="
# five repetitions interleaved at random: the pile's target is a 2-thread figure, and the host's
# slow spells last minutes; summary.py gives the median (and the fastest repetition)
gb_extra="--benchmark_repetitions=5 --benchmark_enable_random_interleaving=true" \
  gbench gb_2t.json 'PileStep|DiskFluid' 2 "$mt"
echo "== cost per particle-step against N (forced disk fluid, 1 thread) =="
# every size on the same CPU: the figure is a ratio between sizes, and the two vCPUs of the
# project's VMs run at different, drifting speeds (docs/threads.md)
pin=()
if command -v taskset >/dev/null; then
  cpu=$(taskset -pc $$ 2>/dev/null | sed 's/.*: //; s/[,-].*//')
  [ -n "$cpu" ] && pin=(taskset -c "$cpu")
fi
# and five repetitions of each size, interleaved at random, so that a slow spell of the host
# falls on every size alike; summary.py gives the ratio of the medians (and of the minima)
pin_cmd="${pin[*]}" gb_extra="--benchmark_repetitions=5 --benchmark_enable_random_interleaving=true" \
  gbench gb_scaling.json 'FluidCostScaling|FluidMixedOrder|SortParticles' 1 "$mt_scan"
echo "== the tapping analysis against its size (10⁴ … 10⁶ taps; the O(N) fit per split) =="
gbench gb_analysis.json 'TapAnalysis' 1 "$mt"
echo "== gransim vs LAMMPS =="
bench/compare_lammps.sh
echo "== seconds per tap; MPI sweep =="
bench/taps.sh
echo
python3 bench/summary.py "$out"
echo "harness wall time: $(( $(date +%s) - t_start )) s (OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-default}; $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg))"

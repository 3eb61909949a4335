#!/usr/bin/env bash
# The benchmark harness: build Release (tools/setup.sh), run the Google Benchmark kernels and
# whole-scene figures, then gransim against LAMMPS. Nothing here is asserted; it prints a table.
set -euo pipefail
cd "$(dirname "$0")/.."
GS_CMAKE_ARGS="-DGS_BUILD_BENCH=ON" tools/setup.sh >/dev/null
echo "== kernels and whole steps (Google Benchmark; 1 thread) =="
OMP_NUM_THREADS=1 build/gransim_bench --benchmark_min_time=1 \
  --benchmark_filter='Decagon|AreaInRect|Pile|Disk|Render|Frame' 2>/dev/null
echo "== the same whole steps with 2 threads =="
OMP_NUM_THREADS=2 build/gransim_bench --benchmark_min_time=1 --benchmark_filter='PileStep|DiskFluid' 2>/dev/null
echo "== gransim vs LAMMPS =="
bench/compare_lammps.sh

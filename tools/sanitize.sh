#!/usr/bin/env bash
# AddressSanitizer + UBSan (the GS_SANITIZE CMake option) in a separate build directory.
#   tools/sanitize.sh [--all] [ctest args...]
# Default (CI): the engine — core, geometry, integrators, scene parsing, broad phase, contacts,
# force laws, drives, the simulation with its checkpoints and state files — built and tested
# with the sanitizers, except the individually slow tests named in $slow. That is where raw
# indices and spans meet particle data; the readers are also fuzzed under ASan/UBSan by
# tools/fuzz.sh, and the plain test suite runs everything. --all builds every target (the
# gransim binary and the tests that drive it, analysis, rendering, output) and runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${GS_ASAN_DIR:-build-asan}
# counted before OMP_NUM_THREADS is set below: GNU nproc honours it
jobs=${GS_JOBS:-$(nproc)}
labels="core|geometry|integrate|scene|broadphase|contact|force|drive|sim"
targets=(--target test_core test_geometry test_integrate test_scene test_broadphase test_contact
         test_force test_drive test_sim)
# each of these runs whole simulations for tens of seconds (Executors: every integrator on three
# scenes, 1 and 2 threads; RunDirLock.AnalysisNever…: every analysis command against every
# protected path; Quench.Off…: whole tapping runs), or starts MPI or several threads
slow="KillResume|^Resume\.|Study|SweepMpi|Threads|ThreadCount|TappingCli|RfmAnalyze|Pile|RunAhead|Demo|Executors"
slow+="|RunDirLock.AnalysisNeverWrites|Quench.OffOrNeverArmed"
exclude=(-E "$slow")
if [ "${1:-}" = "--all" ]; then
  shift
  exclude=()
  labels="$labels|analysis|models|measure|render|output|app"
  targets=()
fi
# -O1 without debug info: quick to compile, fast enough to run, and the sanitizers still name
# file and line through their symbolizer (function names; rebuild with -g for line numbers)
cmake -S . -B "$dir" -DGS_SANITIZE=ON -DGS_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS="-O1 -fno-omit-frame-pointer" -DGS_WITH_MPI=OFF >/dev/null
cmake --build "$dir" -j"$jobs" "${targets[@]}"
# leaks are reported too; halt on the first UBSan finding so it cannot scroll past
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
# Debian's OSMesa keeps a few allocations to the end of the process: not ours (tools/lsan.supp)
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tools/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ctest --test-dir "$dir" --output-on-failure -j"$jobs" -L "$labels" "${exclude[@]}" \
  --timeout 900 "$@"

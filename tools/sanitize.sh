#!/usr/bin/env bash
# AddressSanitizer + UBSan (the GS_SANITIZE CMake option) in a separate build directory.
#   tools/sanitize.sh [--all] [ctest args...]
# Default (CI): every module's tests — core, geometry, integrate, scene, broad phase, contact,
# force laws, analysis, models, and sim, drive, measure, render, output and app, which drive
# the gransim binary built with the sanitizers too — except the individually slow tests named
# in $slow (whole kill-and-resume, study, thread and MPI runs, 2–3× slower under ASan; the
# plain test suite runs them). --all runs those too. The parsers and readers are also fuzzed
# under ASan/UBSan by tools/fuzz.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${GS_ASAN_DIR:-build-asan}
# counted before OMP_NUM_THREADS is set below: GNU nproc honours it
jobs=${GS_JOBS:-$(nproc)}
labels="core|geometry|integrate|scene|broadphase|contact|force|analysis|models|sim|drive|measure|render|output|app"
# each of these runs whole simulations for tens of seconds (Executors: every integrator on three
# scenes, 1 and 2 threads; RunDirLock.AnalysisNever…: every analysis command against every
# protected path; Quench.Off…: whole tapping runs), or starts MPI or several threads
slow="KillResume|^Resume\.|Study|SweepMpi|Threads|ThreadCount|TappingCli|RfmAnalyze|Pile|RunAhead|Demo|Executors"
slow+="|RunDirLock.AnalysisNeverWrites|Quench.OffOrNeverArmed"
exclude=(-E "$slow")
if [ "${1:-}" = "--all" ]; then
  shift
  exclude=()
fi
# -O1 without debug info: quick to compile, fast enough to run, and the sanitizers still name
# file and line through their symbolizer (function names; rebuild with -g for line numbers)
cmake -S . -B "$dir" -DGS_SANITIZE=ON -DGS_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS="-O1 -fno-omit-frame-pointer" -DGS_WITH_MPI=OFF >/dev/null
cmake --build "$dir" -j"$jobs"
# leaks are reported too; halt on the first UBSan finding so it cannot scroll past
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
# Debian's OSMesa keeps a few allocations to the end of the process: not ours (tools/lsan.supp)
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tools/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ctest --test-dir "$dir" --output-on-failure -j"$jobs" -L "$labels" "${exclude[@]}" \
  --timeout 900 "$@"

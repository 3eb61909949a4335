#!/usr/bin/env bash
# AddressSanitizer + UBSan (the GS_SANITIZE CMake option) in a separate build directory.
#   tools/sanitize.sh [--all] [ctest args...]
# Default (CI): the modules below the application — core, geometry, integrate, scene, broad
# phase, contact, force laws, analysis, models — built and tested under the sanitizers (about
# 6 minutes on two cores). --all builds and runs everything (about 25 minutes: the app tests
# run whole simulations, 2–3× slower under ASan). The scene parser and checkpoint reader are
# also fuzzed under ASan/UBSan by tools/fuzz.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${GS_ASAN_DIR:-build-asan}
labels="core|geometry|integrate|scene|broadphase|contact|force|analysis|models"
targets=(test_core test_geometry test_integrate test_scene test_broadphase test_contact
         test_force test_analysis test_models)
if [ "${1:-}" = "--all" ]; then
  shift
  labels=""
  targets=(all)
fi
# -O1 without debug info: quick to compile, fast enough to run, and the sanitizers still name
# file and line through their symbolizer (function names; rebuild with -g for line numbers)
cmake -S . -B "$dir" -DGS_SANITIZE=ON -DGS_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_CXX_FLAGS="-O1 -fno-omit-frame-pointer" -DGS_WITH_MPI=OFF >/dev/null
cmake --build "$dir" -j"${GS_JOBS:-$(nproc)}" --target "${targets[@]}"
# leaks are reported too; halt on the first UBSan finding so it cannot scroll past
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
if [ -n "$labels" ]; then
  ctest --test-dir "$dir" --output-on-failure -j"${GS_JOBS:-$(nproc)}" -L "$labels" "$@"
else
  ctest --test-dir "$dir" --output-on-failure -j"${GS_JOBS:-$(nproc)}" "$@"
fi

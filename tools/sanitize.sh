#!/usr/bin/env bash
# configure a separate build with AddressSanitizer + UBSan (the GS_SANITIZE CMake option),
# build everything and run the test suite under the sanitizers.
#   tools/sanitize.sh [BUILD_DIR] [ctest args...]     (default build-asan)
# A full rebuild: about 10 minutes on two busy cores. Benchmarks are left out.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build-asan}
shift || true
cmake -S . -B "$dir" -DGS_SANITIZE=ON -DGS_BUILD_BENCH=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$dir" -j"${JOBS:-2}"
# leaks are reported too; halt on the first UBSan finding so it cannot scroll past
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ctest --test-dir "$dir" --output-on-failure -j"${JOBS:-2}" "$@"

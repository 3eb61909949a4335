#!/usr/bin/env bash
# Set up (tools/setup.sh) and run the whole test suite with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
build=${GS_BUILD_DIR:-build}
cd "$build"
ctest --output-on-failure -j "${GS_JOBS:-$(nproc)}" --timeout 900 "$@"

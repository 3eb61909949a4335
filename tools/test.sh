#!/usr/bin/env bash
# Set up (tools/setup.sh) and run the whole test suite with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
# the tests alone need a browser: the reproduction report is opened in headless Chromium
if ! dpkg-query -W -f='${Status}' chromium 2>/dev/null | grep -q "install ok installed"; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends chromium
fi
build=${GS_BUILD_DIR:-build}
cd "$build"
ctest --output-on-failure -j "${GS_JOBS:-$(nproc)}" --timeout 900 "$@"

#!/usr/bin/env bash
# Set up (tools/setup.sh) and run the whole test suite with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
# the tests alone need a browser (the reproduction report is opened in headless Chromium) and
# pandas (tests/tools/test_python_outputs.py reads every CSV with it)
missing=()
for pkg in chromium python3-pandas; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ "${#missing[@]}" -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
build=${GS_BUILD_DIR:-build}
cd "$build"
ctest --output-on-failure -j "${GS_JOBS:-$(nproc)}" --timeout 900 "$@"

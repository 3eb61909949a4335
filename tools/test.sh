#!/usr/bin/env bash
# Set up (tools/setup.sh: packages, then every target) and run the whole test suite with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh all
# what the tests alone need: clang-format (the sources are checked against .clang-format), a
# browser (the reproduction report is opened in headless Chromium), the readers the snapshot
# files are checked with (ASE, VTK, pandas; h5py and MDAnalysis for the H5MD trajectory),
# pytest (the Python module's tests, tests/python/), Hypothesis (random arguments thrown at
# every function of the module, tests/python/test_fuzz.py) and Debian's venv, pip, setuptools
# and wheel (`pip install .` into a venv, offline)
test_packages=(clang-format chromium python3-ase python3-vtk9 python3-pandas python3-pytest
               python3-hypothesis python3-venv python3-pip python3-setuptools python3-wheel
               python3-h5py python3-mdanalysis)
missing=()
for p in "${test_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
build=${GS_BUILD_DIR:-build}
cd "$build"
ctest --output-on-failure -j "${GS_JOBS:-$(nproc)}" --timeout 900 "$@"

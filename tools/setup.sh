#!/usr/bin/env bash
# Fresh-machine setup: install exactly the Debian packages the build needs, then configure and
# build (Release) into build/. Safe to run again: installed packages are skipped.
# usage: tools/setup.sh [TARGET...]   (default: gransim, the program alone, so that the demo runs
# soon; tools/test.sh builds `all`: the tests, the Python module, the benchmarks)
# Environment: CI=true turns warnings into errors; GS_BUILD_DIR (default build); GS_JOBS.
# Compiles go through ccache, so a second build tree (the pip install's) reuses the objects.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake pkg-config git ccache
  libeigen3-dev libbox2d-dev libtomlplusplus-dev libcli11-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libpng-dev libfftw3-dev libfreetype-dev fonts-dejavu-core
  libosmesa6-dev libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
  libopenmpi-dev openmpi-bin
  nlohmann-json3-dev libhdf5-dev zlib1g-dev
  python3 python3-numpy python3-matplotlib python3-pybind11 python3-dev
)

# install what is missing (apt-get update first, as a fresh machine's lists may be empty)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# configure and build
build=${GS_BUILD_DIR:-build}
werror=OFF
[ "${CI:-}" = "true" ] && werror=ON
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGS_WERROR=$werror \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache ${GS_CMAKE_ARGS:-} >/dev/null
targets=("${@:-gransim}")
cmake --build "$build" -j "${GS_JOBS:-$(nproc)}" --target "${targets[@]}"
echo "setup: built ${targets[*]} in $build"

#!/usr/bin/env bash
# build the libFuzzer targets in fuzz/ with clang (ASan + UBSan) and run each for N seconds.
#   tools/fuzz.sh [SECONDS] [TARGET...]
#   (default 30 s each; targets: scene checkpoint state csv restore; the last three get a third
#   of SECONDS each, so `tools/fuzz.sh 30` fuzzes for about 2.5 minutes in all)
# Binaries and grown corpora go to build-fuzz/; crashes to build-fuzz/crashes/<target>/.
# Each target compiles only the sources it needs (scene: src/{scene,geometry} and the integrators' names;
# checkpoint: the decoder; state: + world and the state-file reader; csv: src/analysis;
# restore: the simulation modules), so no full rebuild is needed.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-30}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(scene checkpoint state csv restore)

# clang and the sanitizer/fuzzer runtimes (Debian bookworm: clang-14)
sudo_() { if [ "$(id -u)" = 0 ]; then "$@"; else sudo "$@"; fi; }
CXX=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$CXX" ] || ! dpkg -s libclang-rt-14-dev >/dev/null 2>&1; then
  sudo_ apt-get update
  sudo_ apt-get install -y clang-14 libclang-rt-14-dev
  CXX=$(command -v clang++-14)
fi

out=build-fuzz
mkdir -p "$out"
flags=(-std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined
       -Isrc -isystem /usr/include/eigen3 -DTOML_HEADER_ONLY=1
       # toml++ internal asserts off, as in the shipped library (Debian builds it with NDEBUG and
       # GCC, where TOML_ASSERT_ASSUME is a no-op): the debug-only asserts are known upstream
       # (marzer/tomlplusplus#294, #301) and would stop every run at the first malformed header
       "-DTOML_ASSERT(expr)=static_cast<void>(0)")

# one binary per target, compiled in one clang call (a minute or two on a loaded machine)
build() {
  local name=$1
  shift
  if [ ! -x "$out/fuzz_$name" ] || [ -n "$(find fuzz src -newer "$out/fuzz_$name" -name '*.?pp' | head -1)" ]; then
    echo "building fuzz_$name" >&2
    "$CXX" "${flags[@]}" "$@" -o "$out/fuzz_$name"
  fi
}
# the targets are compiled side by side (one clang call each, single-threaded): on a 2-core
# machine the builds take half the wall time they take one after the other
pids=()
build_all() {
  for t in "${targets[@]}"; do
    build_one "$t" &
    pids+=($!)
  done
}
build_one() {
  local t=$1
  case $t in
    scene) build scene fuzz/fuzz_scene.cpp src/scene/*.cpp src/geometry/*.cpp src/core/integrator_kind.cpp \
             src/core/input_file.cpp ;;
    checkpoint) build checkpoint fuzz/fuzz_checkpoint.cpp src/sim/checkpoint_read.cpp \
                  src/core/input_file.cpp ;;
    state) build state fuzz/fuzz_state.cpp src/sim/state_file.cpp src/world/*.cpp \
             src/scene/*.cpp src/geometry/*.cpp src/integrate/*.cpp src/core/*.cpp \
             src/output/run_dir.cpp ;;
    csv) build csv fuzz/fuzz_csv.cpp src/analysis/*.cpp src/core/*.cpp ;;
    restore) build restore fuzz/fuzz_restore.cpp src/sim/*.cpp src/world/*.cpp src/scene/*.cpp \
               src/geometry/*.cpp src/integrate/*.cpp src/core/*.cpp src/broadphase/*.cpp \
               src/contact/*.cpp src/force/*.cpp src/force/laws/*.cpp src/drive/*.cpp \
               src/output/run_dir.cpp src/output/csv.cpp -lbox2d ;;
    *) echo "unknown target $t (scene, checkpoint, state, csv, restore)" >&2; exit 2 ;;
  esac
}
for t in "${targets[@]}"; do
  case $t in
    scene | checkpoint | state | csv | restore) ;;
    *) echo "unknown target $t (scene, checkpoint, state, csv, restore)" >&2; exit 2 ;;
  esac
done
build_all
for p in "${pids[@]}"; do
  wait "$p" || { echo "fuzz: a target did not compile" >&2; exit 1; }
done

# run: seeds from fuzz/corpus/<target>, the grown corpus kept in build-fuzz/corpus/<target>
status=0
for t in "${targets[@]}"; do
  mkdir -p "$out/corpus/$t" "$out/crashes/$t"
  dict=()
  [ -f "fuzz/$t.dict" ] && dict=(-dict="fuzz/$t.dict")
  seeds=()
  [ -d "fuzz/corpus/$t" ] && seeds=("fuzz/corpus/$t")
  [ "$t" = restore ] && seeds=("fuzz/corpus/checkpoint")
  t_secs=$secs
  case $t in state | csv | restore) t_secs=$(((secs + 2) / 3)) ;; esac
  echo "fuzzing $t for $t_secs s" >&2
  if ! "$out/fuzz_$t" "$out/corpus/$t" "${seeds[@]}" "${dict[@]}" -max_total_time="$t_secs" \
      -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$out/crashes/$t/" 2>&1 | tail -n 25; then
    status=1
  fi
  [ "${PIPESTATUS[0]}" = 0 ] || status=1
done
exit $status

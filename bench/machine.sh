#!/usr/bin/env bash
# the machine a harness run measured, as "key value" lines (bench/summary.py prints them above
# its table): CPU model, x86 family and model, the cores' L2, vector extensions, clock, cores
set -u
field() { grep -m1 "^$1[[:space:]]*:" /proc/cpuinfo 2>/dev/null | sed 's/^[^:]*: *//'; }
echo "cpu $(field 'model name')"
echo "family $(field 'cpu family')"
echo "model $(field 'model')"
l2=$(cat /sys/devices/system/cpu/cpu0/cache/index2/size 2>/dev/null || echo '?')
echo "l2 $l2"
flags=" $(field flags) "
ext=""
for f in avx2 fma avx512f; do [[ $flags == *" $f "* ]] && ext="$ext $f"; done
echo "vector ${ext# }"
echo "mhz $(field 'cpu MHz')"
echo "cpus $(nproc)"

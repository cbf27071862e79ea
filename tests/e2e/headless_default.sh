#!/bin/bash
# On a machine with no display, `sketch-a-scratch` with no command runs
# the headless visit in under a minute and exits 0; headless_check then checks every output.
# usage: headless_default.sh <sketch-a-scratch> <headless_check> [max seconds [extra options]]
set -u
app=$1
check=$2
max_s=${3:-60}
extra=${4:-}
work=$(mktemp -d /tmp/sas-headless-XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# No display of any kind: the default must choose the headless visit by itself.
unset DISPLAY WAYLAND_DISPLAY SDL_VIDEODRIVER
start_ms=$(($(date +%s%N) / 1000000))
"$app" --out "$work/out" $extra >"$work/log" 2>&1
rc=$?
elapsed_ms=$(($(date +%s%N) / 1000000 - start_ms))
cat "$work/log" | grep -v '^  [a-z]* *\(found\|NOT FOUND\)'
[ $rc = 0 ] || { echo "FAIL: exit code $rc"; exit 1; }
grep -q "writing to $work/out" "$work/log" || { echo "FAIL: the output folder is not printed"; exit 1; }
echo "headless visit took ${elapsed_ms} ms (limit ${max_s} s)"
[ "$elapsed_ms" -lt $((max_s * 1000)) ] || { echo "FAIL: took longer than ${max_s} s"; exit 1; }
"$check" "$work/out"

#!/bin/bash
# On a machine with no display, `sketch-a-scratch` with no command runs the headless visit and
# exits 0; headless_check then checks every output. The visit runs on a virtual clock, so how long
# it takes is only the machine's speed: it is printed (well under a minute on a quiet machine),
# and the bound is there for a visit that hangs, generous because a busy machine (CI, a
# packager's build) takes several times longer.
# usage: headless_default.sh <sketch-a-scratch> <headless_check> [bound in seconds [extra options]]
set -u
app=$1
check=$2
max_s=${3:-600}
extra=${4:-}
work=$(mktemp -d /tmp/sas-headless-XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
# No display of any kind: the default must choose the headless visit by itself. No session
# either (CI, a system service): without XDG_RUNTIME_DIR the display probe (SDL's wayland driver) made
# libwayland print an error on stderr, which must stay empty on a machine that works as meant
# (what is missing is the hardware report's business, on stdout).
unset DISPLAY WAYLAND_DISPLAY WAYLAND_SOCKET SDL_VIDEODRIVER XDG_RUNTIME_DIR
start_ms=$(($(date +%s%N) / 1000000))
timeout "$max_s" "$app" --out "$work/out" $extra >"$work/log" 2>"$work/err"
rc=$?
elapsed_ms=$(($(date +%s%N) / 1000000 - start_ms))
cat "$work/log" | grep -v '^  [a-z]* *\(found\|NOT FOUND\)'
if [ -s "$work/err" ]; then
  echo "FAIL: the headless run wrote on stderr:"
  sed 's/^/    /' "$work/err"
  exit 1
fi
echo "headless visit took ${elapsed_ms} ms (bound ${max_s} s; load average $(cut -d' ' -f1-3 /proc/loadavg))"
[ $rc != 124 ] || { echo "FAIL: not done within ${max_s} s"; exit 1; }
[ $rc = 0 ] || { echo "FAIL: exit code $rc"; exit 1; }
grep -q "writing to $work/out" "$work/log" || { echo "FAIL: the output folder is not printed"; exit 1; }
"$check" "$work/out"

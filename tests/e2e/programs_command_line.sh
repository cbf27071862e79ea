#!/bin/bash
# Every program the build makes (the list comes from the build: cmake/SasPrograms.cmake) answers
# --help with exit 0, its usage on stdout and nothing on stderr, and an unknown flag with exit 2,
# nothing on stdout and an error naming the flag on stderr. Run as CI runs them: no display, no
# sound server (XDG_RUNTIME_DIR unset), and a working folder and HOME of their own that must stay
# empty (a flag taken for a file name once became a folder of four textures). Each run is bounded
# only against a hang.
# usage: programs_command_line.sh <program>...
set -u
[ $# -gt 0 ] || { echo "FAIL: no programs given"; exit 1; }
work=$(mktemp -d /tmp/sas-programs-XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/cwd" "$work/home"
unset DISPLAY WAYLAND_DISPLAY SDL_VIDEODRIVER XDG_RUNTIME_DIR XDG_STATE_HOME STATE_DIRECTORY
export HOME="$work/home"
failures=0
fail() {  # fail <what>: says what, with the start of both streams
  echo "FAIL: $1"
  sed 's/^/    out: /' "$work/out" | head -3
  sed 's/^/    err: /' "$work/err" | head -3
  failures=$((failures + 1))
}
run() {  # run <program> <args...>: exit code in $rc, streams in $work/out and $work/err
  (cd "$work/cwd" && timeout 120 "$@" >"$work/out" 2>"$work/err" </dev/null)
  rc=$?
}
t0=$(date +%s%N)
for program in "$@"; do
  program=$(readlink -f "$program")  # they run in a folder of their own
  name=$(basename "$program")
  run "$program" --help
  if [ $rc != 0 ]; then
    fail "$name --help -> exit $rc (want 0)"
  elif ! grep -q "^Usage: .*$name" "$work/out"; then
    fail "$name --help printed no usage line naming it on stdout"
  elif [ -s "$work/err" ]; then
    fail "$name --help wrote on stderr"
  fi
  run "$program" --no-such-flag
  if [ $rc != 2 ]; then
    fail "$name --no-such-flag -> exit $rc (want 2)"
  elif ! grep -q -- "--no-such-flag" "$work/err"; then
    fail "$name --no-such-flag did not name the flag on stderr"
  elif [ -s "$work/out" ]; then
    fail "$name --no-such-flag wrote on stdout"
  fi
  written=$(cd "$work" && find cwd home -mindepth 1)
  if [ -n "$written" ]; then
    echo "FAIL: $name wrote files:" $written
    failures=$((failures + 1))
    find "$work/cwd" "$work/home" -mindepth 1 -delete
  fi
done
echo "$# programs in $((($(date +%s%N) - t0) / 1000000)) ms"
[ $failures = 0 ] && echo PASS
exit $((failures > 0))

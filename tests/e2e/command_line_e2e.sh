#!/bin/bash
# The real binary's command line: every command answers --help with 0, usage errors exit 2 naming
# the option, and the kiosk with no display exits 1 at once and writes nothing into HOME (it once
# ran for ever on SDL's offscreen driver, counting visits there). Each command is bounded only
# against a hang, generously (a busy machine is slow, not wrong), and says how long it took.
# usage: command_line_e2e.sh <sketch-a-scratch>
set -u
app=$1
work=$(mktemp -d /tmp/sas-cli-XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
unset DISPLAY WAYLAND_DISPLAY SDL_VIDEODRIVER XDG_STATE_HOME STATE_DIRECTORY
export HOME="$work/home"
mkdir -p "$HOME"
failures=0
bound_s=120
expect() {  # expect <exit code> <text in stdout+stderr> <args...>
  local want=$1 text=$2 t0 ms
  shift 2
  t0=$(date +%s%N)
  timeout "$bound_s" "$app" "$@" >"$work/out" 2>&1
  local rc=$?
  ms=$((($(date +%s%N) - t0) / 1000000))
  if [ $rc = 124 ]; then
    echo "FAIL: sketch-a-scratch $* still running after ${bound_s} s"
    failures=$((failures + 1))
  elif [ $rc != "$want" ] || ! grep -q -- "$text" "$work/out"; then
    echo "FAIL: sketch-a-scratch $* -> exit $rc (want $want, text '$text')"
    sed 's/^/    /' "$work/out" | head -5
    failures=$((failures + 1))
  else
    echo "ok: sketch-a-scratch $* -> $rc (${ms} ms)"
  fi
}
for command in "" demo kiosk render impact texture "texture new" "texture check" "texture preview" "texture install"; do
  # shellcheck disable=SC2086
  expect 0 "--help" $command --help
done
expect 0 "sketch-a-scratch" --version
expect 2 "--config: 1 required TEXT missing" kiosk --config
expect 2 "--state-dir" --kiosk --state-dir
expect 2 "--fullscreen" kiosk --fullscreen
expect 2 "--out" demo --out
expect 2 "bogus" bogus
expect 2 "--token" texture install x --token 9
expect 2 "--photo" texture new x --photo
expect 1 "not a folder" texture check /nonexistent/folder
expect 2 "--out" --out
expect 2 "--fs" render --out x.wav --fs 1e30
expect 2 "--mass" impact --mass nan
expect 0 "glass on broken_glass" render --texture broken_glass --gesture tap --tail-s 0.1 --out g.wav
expect 1 "no display" kiosk
expect 1 "no display" --kiosk --config /nonexistent.toml
[ -z "$(ls -A "$HOME")" ] || { echo "FAIL: the kiosk wrote into HOME: $(find "$HOME")"; failures=$((failures + 1)); }
[ $failures = 0 ] && echo PASS
exit $((failures > 0))

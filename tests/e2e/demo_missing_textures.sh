#!/bin/bash
# `demo` with fewer than four loadable textures: the visit runs with the textures that load, says
# on the console and in visit.txt which steps it skipped, and exits 0. Two cases: one texture
# broken (three left), and three broken (one left: no token switch, no bubble pop). The demo runs
# on a virtual clock: its run time is only the machine's speed, printed; the bound is against a
# hang, generous for a busy machine.
# usage: demo_missing_textures.sh <sketch-a-scratch> <source textures folder>
set -u
app=$1
textures=$2
work=$(mktemp -d /tmp/sas-demo-missing-XXXXXX)
trap 'rm -rf "$work"' EXIT
unset DISPLAY WAYLAND_DISPLAY SDL_VIDEODRIVER
fail() { echo "FAIL: $*"; cat "$work/log" 2>/dev/null | tail -20; exit 1; }

run_case() {  # run_case <name> <broken texture>...
  local name=$1
  shift
  local data="$work/$name"
  mkdir -p "$data/textures"
  for key in bubble_wrap broken_glass wooden_board cracked_ground; do
    cp -r "$textures/$key" "$data/textures/"
  done
  for key in "$@"; do echo "height_map = [" >"$data/textures/$key/texture.toml"; done
  local t0=$(($(date +%s%N) / 1000000))
  SAS_DATA_DIR="$data" timeout 600 "$app" demo --quick --out "$data/out" >"$work/log" 2>&1
  local rc=$?
  echo "$name: the demo took $(($(date +%s%N) / 1000000 - t0)) ms"
  [ $rc != 124 ] || fail "$name: not done within 600 s"
  [ $rc = 0 ] || fail "$name: exit code $rc"
  for key in "$@"; do
    grep -q "skipped: texture $key" "$work/log" || fail "$name: no console line for $key"
    grep -q "skipped texture $key" "$data/out/visit.txt" || fail "$name: visit.txt misses $key"
    [ ! -e "$data/out/${key}_scrape.wav" ] || fail "$name: a stroke on missing $key was written"
  done
  ls "$data/out"/*_scrape.wav >/dev/null 2>&1 || fail "$name: no stroke on the textures left"
  echo "$name: ok"
}

run_case one_missing broken_glass
run_case three_missing bubble_wrap broken_glass cracked_ground
grep -q "skipped: the token switch" "$work/log" || fail "one texture: the token switch not skipped"
grep -q "skipped: the bubble pop" "$work/log" || fail "one texture: the bubble pop not skipped"
echo "PASS"

#!/usr/bin/env bash
# Screenshot of the live kiosk's staff panel on Xvfb at one size (docs/screenshots/): the kiosk
# binary with keyboard switches and no sound card, the staff chord held, the X root window saved.
#   staff_panel_screenshot.sh <sketch-a-scratch> <width> <height> <out.jpg>
set -euo pipefail
app="$1"
width="$2"
height="$3"
out="$4"
work=$(mktemp -d /tmp/sas-staff-shot-XXXXXX)
cleanup() {
  [ -n "${app_pid:-}" ] && kill "$app_pid" 2>/dev/null && wait "$app_pid" 2>/dev/null
  [ -n "${xvfb_pid:-}" ] && kill "$xvfb_pid" 2>/dev/null && wait "$xvfb_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/state"
printf '[switches]\nbackend = "keyboard"\n' >"$work/kiosk.toml"
Xvfb -displayfd 3 -screen 0 "${width}x${height}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
export DISPLAY=":$(cat "$work/display")" SDL_VIDEODRIVER=x11
"$app" kiosk --config "$work/kiosk.toml" --state-dir "$work/state" >"$work/app.log" 2>&1 &
app_pid=$!
for _ in $(seq 120); do grep -q '^kiosk ready' "$work/app.log" && break; sleep 0.5; done
xdotool keydown ctrl+alt+s
sleep 1.3  # the chord is held 1 s
xdotool keyup s alt ctrl
sleep 1
import -window root -quality 85 "$out"
echo "staff panel at ${width}x${height}: $out"

#!/usr/bin/env bash
# Screenshot of the live kiosk's staff panel on Xvfb at one size (docs/screenshots/): the kiosk
# binary with keyboard switches and no sound card, the staff chord held, the X root window saved.
# Each step waits for its event (the kiosk's log line, the panel on the screen), not a fixed time.
#   staff_panel_screenshot.sh <sketch-a-scratch> <width> <height> <out.jpg>
set -euo pipefail
app="$1"
width="$2"
height="$3"
out="$4"
work=$(mktemp -d /tmp/sas-staff-shot-XXXXXX)
. "$(dirname "${BASH_SOURCE[0]}")/xvfb_common.sh"
cleanup() {
  [ -n "${app_pid:-}" ] && stop_pid "$app_pid"
  [ -n "${xvfb_pid:-}" ] && stop_pid "$xvfb_pid"
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "staff_panel_screenshot: $*"; cat "$work/app.log" 2>/dev/null; exit 1; }
mkdir -p "$work/state"
printf '[switches]\nbackend = "keyboard"\n' >"$work/kiosk.toml"
start_xvfb "$width" "$height" || fail "Xvfb did not start"
export SDL_VIDEODRIVER=x11
log_has() { grep -q -- "$1" "$work/app.log" 2>/dev/null; }
"$app" kiosk --config "$work/kiosk.toml" --state-dir "$work/state" >"$work/app.log" 2>&1 &
app_pid=$!
watch=$app_pid
until_true "log: kiosk ready" log_has '^kiosk ready' || fail "the kiosk never got ready"
# Held until the kiosk says the panel opened (1 s by its own clock).
xdotool keydown ctrl+alt+s
opened=0
until_true "log: staff panel opened" log_has 'staff panel opened' || opened=1
xdotool keyup s alt ctrl
[ $opened = 0 ] || fail "the staff chord did not open the panel"
# The panel's dark plate dominates the middle of the screen once it is drawn.
panel_drawn() {
  local mean
  mean=$(convert "$work/panel.png" -crop 40x40+$((width / 2 - 20))+$((height / 2 - 20)) +repage \
    -format '%[fx:int(255*mean.r)]' info:) || return 1
  [ "$mean" -lt 90 ]
}
shot_until panel "the staff panel" panel_drawn || fail "no staff panel on the screen"
convert "$work/panel.png" -quality 85 "$out"
echo "staff panel at ${width}x${height}: $out"

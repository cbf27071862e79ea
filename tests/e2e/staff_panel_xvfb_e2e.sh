#!/usr/bin/env bash
# The live kiosk's staff panel on a real X server at one size: the kiosk binary under Xvfb with
# keyboard switches and no sound card (as staff_panel_screenshot.sh), the staff chord held, the
# root window saved as PNG (lossless: the contrast is measured on exact pixels) and checked by
# staff_panel_check: the panel's text and button labels at 7:1 or more against what is behind
# them, its lines drawn in normal case and the configuration path as given (all lower case here,
# so capitals would show).
#   staff_panel_xvfb_e2e.sh <sketch-a-scratch> <staff_panel_check> <textures dir> <width> <height>
set -euo pipefail
app="$1"
check="$2"
textures="$3"
width="$4"
height="$5"
for t in Xvfb xdotool import; do
  command -v "$t" >/dev/null || { echo "SKIP: $t not installed (install/packages.txt, test)"; exit 77; }
done
# A lower-case folder of our own (mktemp's letters are mixed case).
work="/tmp/sas-staff-panel-$$-$(date +%s%N)"
mkdir "$work"
. "$(dirname "${BASH_SOURCE[0]}")/xvfb_common.sh"
cleanup() {
  [ -n "${app_pid:-}" ] && stop_pid "$app_pid"
  [ -n "${xvfb_pid:-}" ] && stop_pid "$xvfb_pid"
  [ -n "${SAS_E2E_KEEP:-}" ] && cp "$work/panel.png" "$work/app.log" "$SAS_E2E_KEEP"/ 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- kiosk log"; cat "$work/app.log" 2>/dev/null; exit 1; }
mkdir -p "$work/state" "$work/etc/sketch-a-scratch"
config="$work/etc/sketch-a-scratch/kiosk.toml"
# No passive strokes: the picture under the panel stays the texture's picture, undented.
printf '[switches]\nbackend = "keyboard"\n[session]\ndefault_texture = "wooden_board"\n[attract]\npassive_stroke = false\n' >"$config"
Xvfb -displayfd 3 -screen 0 "${width}x${height}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || fail "Xvfb did not start: $(cat "$work/xvfb.log")"
export DISPLAY=":$(cat "$work/display")" SDL_VIDEODRIVER=x11
unset WAYLAND_DISPLAY
"$app" kiosk --config "$config" --state-dir "$work/state" >"$work/app.log" 2>&1 &
app_pid=$!
for _ in $(seq 600); do  # up to 60 s, for a loaded machine
  grep -q '^kiosk ready' "$work/app.log" && break
  kill -0 "$app_pid" 2>/dev/null || fail "the kiosk ended before it was ready"
  sleep 0.1
done
grep -q "^kiosk ready ${width}x${height} " "$work/app.log" || fail "the kiosk is not ready full-screen at ${width}x${height}"
xdotool keydown ctrl+alt+s
sleep 1.3  # the chord is held 1 s
xdotool keyup s alt ctrl
for _ in $(seq 50); do grep -q 'staff panel opened' "$work/app.log" && break; sleep 0.1; done
grep -q 'staff panel opened' "$work/app.log" || fail "the staff chord did not open the panel"
sleep 1  # the panel's lines are rebuilt 4 times a second; the frame after that is on screen
import -window root "$work/panel.png" || fail "screenshot failed"
"$check" "$work/panel.png" "$textures/wooden_board/picture.png" "$config" || fail "staff panel check at ${width}x${height}"

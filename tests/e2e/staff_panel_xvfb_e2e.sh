#!/usr/bin/env bash
# The live kiosk's staff panel on a real X server at one size: the kiosk binary under Xvfb with
# keyboard switches and no sound card (as staff_panel_screenshot.sh), the staff chord held, the
# root window saved as PNG (lossless: the contrast is measured on exact pixels) and checked by
# staff_panel_check: the panel's text and button labels at 7:1 or more against what is behind
# them, its lines drawn in normal case and the configuration path as given (all lower case here,
# so capitals would show). Each step waits for its event (the kiosk's log line, a screenshot that
# passes the check) with xvfb_common.sh's generous deadline.
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
start_xvfb "$width" "$height" || fail "Xvfb did not start"
export SDL_VIDEODRIVER=x11
unset WAYLAND_DISPLAY
log_has() { grep -q -- "$1" "$work/app.log" 2>/dev/null; }
"$app" kiosk --config "$config" --state-dir "$work/state" >"$work/app.log" 2>&1 &
app_pid=$!
watch=$app_pid  # a wait ends at once when the kiosk is gone
until_true "log: kiosk ready" log_has '^kiosk ready' || fail "the kiosk ended or never got ready"
grep -q "^kiosk ready ${width}x${height} " "$work/app.log" || fail "the kiosk is not ready full-screen at ${width}x${height}"
# The chord is held until the kiosk says the panel opened (it must be held 1 s by the kiosk's own
# clock, which a busy machine can start late).
xdotool keydown ctrl+alt+s
opened=0
until_true "log: staff panel opened" log_has 'staff panel opened' || opened=1
xdotool keyup s alt ctrl
[ $opened = 0 ] || fail "the staff chord did not open the panel"
# The panel is on the screen some frames after the log line (its lines are rebuilt 4 times a
# second): screenshots until one passes the check.
shot_until panel "the staff panel passing its check" \
  "$check" "$work/panel.png" "$textures/wooden_board/picture.png" "$config" ||
  fail "staff panel check at ${width}x${height}"

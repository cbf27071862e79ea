#!/bin/bash
# End-to-end check of the ui layer on a real X server: Xvfb (no window manager), the ui driver
# program full-screen, a pointer drag with xdotool, ImageMagick screenshots.
# Checks: the window covers the whole screen; while the button is held the screenshot shows the
# dent at the drag point and the picture everywhere else; after release the picture comes back
# exactly and no frames are drawn at rest; visitor key combinations (Alt-F4, Escape, Ctrl-Q, Ctrl-W, Ctrl-Alt-BackSpace) leave it
# running; the staff chord opens the staff panel.
# Every step waits for its event (a line the driver prints, a screenshot that passes its check)
# with xvfb_common.sh's generous deadline, and says how long it waited.
# usage: ui_xvfb_e2e.sh <ui_e2e_app> [picture|checker]
set -u
app=$1
picture=${2:-checker}
width=1280
height=720
for tool in Xvfb xdotool import; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool not installed (install/packages.txt, test group)"; exit 1; }
done
work=$(mktemp -d /tmp/sas-ui-e2e-XXXXXX)
xvfb_pid=""
app_pid=""
# stop_pid, the waits, and no LeakSanitizer exit scan (as the other Xvfb tests).
. "$(dirname "${BASH_SOURCE[0]}")/xvfb_common.sh"
cleanup() {
  [ -n "$app_pid" ] && stop_pid "$app_pid"
  [ -n "$xvfb_pid" ] && stop_pid "$xvfb_pid"
  # SAS_E2E_KEEP=<dir> keeps the screenshots and the app log for a look.
  [ -n "${SAS_E2E_KEEP:-}" ] && cp "$work"/*.png "$work/app.log" "$SAS_E2E_KEEP"/ 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- app log"; cat "$work/app.log"; exit 1; }
log_has() { grep -q -- "$1" "$work/app.log" 2>/dev/null; }
wait_log() { until_true "log: $1" log_has "$1"; }

start_xvfb "$width" "$height" || fail "Xvfb did not start"
unset WAYLAND_DISPLAY SDL_VIDEODRIVER

# The driver ends by itself after this many seconds (a copy left behind by a killed test does not
# live on); far more than the whole test takes on a busy machine.
"$app" window "$picture" 1800 >"$work/app.log" 2>&1 &
app_pid=$!
watch=$app_pid  # a wait ends at once when the app is gone
# Wait for the app's "ready" first: renderer set-up on llvmpipe can take seconds, and SDL may
# replace its first X window by one with an OpenGL visual while it creates the renderer, so a
# window found earlier can vanish.
wait_log '^ready' || fail "app never reported ready"
window_id=$(timeout "$e2e_wait_s" xdotool search --sync --onlyvisible --name '^Sketch-a-Scratch$' | head -1)
[ -n "$window_id" ] || fail "no window appeared"
echo "$(head -1 "$work/app.log")"

eval "$(xdotool getwindowgeometry --shell "$window_id")"
[ "$WIDTH" = "$width" ] && [ "$HEIGHT" = "$height" ] && [ "$X" = 0 ] && [ "$Y" = 0 ] ||
  fail "window is ${WIDTH}x${HEIGHT}+${X}+${Y}, not full-screen ${width}x${height}+0+0"
echo "ok: window covers the screen (${WIDTH}x${HEIGHT})"

# Drag with the button held; xdotool jumps between points, so interpolate the stroke.
x0=400; y0=360; x1=640; y1=420; steps=24
xdotool mousemove $x0 $y0
sleep 0.2  # part of the gesture: the pointer rests at the start before the button goes down
stroke=(mousedown 1)
for i in $(seq 1 $steps); do
  stroke+=(sleep 0.016 mousemove $((x0 + (x1 - x0) * i / steps)) $((y0 + (y1 - y0) * i / steps)))
done
xdotool "${stroke[@]}"  # one xdotool process: even timing at ~60 Hz
wait_log "^down $x0 $y0" || fail "no pointer-down at $x0,$y0"
# The button stays down until a screenshot shows the dent under the drag's end.
shot_until held "the dent at the drag point" "$app" check "$work/held.png" "$picture" $x1 $y1 ||
  fail "no dent at the drag point in the screenshot"
echo "ok: dent visible at the drag point, picture unchanged elsewhere"
xdotool mouseup 1
wait_log '^up ' || fail "the release did not arrive"
# Release time constant 0.12 s: the screen comes back to the picture exactly.
restored() {
  local figures
  figures=$("$app" check "$work/released.png" "$picture" $x1 $y1)
  echo "$figures"
  grep -q "near-dent mean difference 0.00" <<<"$figures"
}
shot_until released "the picture restored after the release" restored ||
  fail "picture not restored after release"
echo "ok: picture restored after release"

# Redraw only while something changes: at rest the frame counter stands still. The app prints it
# about once a second of its own time; the 2nd report after the release comes over a second
# after it (the deformation is at rest well within that), and from there to the 4th, two more
# seconds by the app's clock, not one frame may be drawn.
frames_after_release() { sed -n '/^up /,$p' "$work/app.log" | grep '^frames' | cut -d' ' -f2; }
four_reports() { [ "$(frames_after_release | wc -l)" -ge 4 ]; }
until_true "4 frame counter reports after the release" four_reports || fail "the frame counter stopped"
before=$(frames_after_release | sed -n 2p)
after=$(frames_after_release | sed -n 4p)
[ -n "$before" ] && [ "$before" = "$after" ] || fail "frames drawn while idle ($before -> $after)"
echo "ok: no frames while nothing changes (frame counter stays at $after)"

for combo in alt+F4 Escape ctrl+q ctrl+w ctrl+alt+BackSpace alt+Tab super; do
  xdotool key "$combo"
done
# Staff chord: Ctrl+Alt+S, held (0.3 s in the driver program) until the driver says the panel
# opened. It comes after the combinations in the one event queue: once it is handled they were,
# and the app still runs.
xdotool keydown ctrl+alt+s
wait_log '^staff open'
opened=$?
xdotool keyup s alt ctrl
kill -0 "$app_pid" 2>/dev/null || fail "a visitor key combination ended the app"
[ $opened = 0 ] || fail "staff chord did not open the staff panel"
echo "ok: Alt-F4, Escape, Ctrl-Q, Ctrl-W, Ctrl-Alt-BackSpace, Alt-Tab, Super leave it running"
panel_drawn() {
  convert "$work/staff.png" -crop 1x1+$((width / 2))+$((height / 2)) -format '%[fx:int(255*r)]' info: \
    >"$work/panel.txt" || return 1
  echo "centre red level $(cat "$work/panel.txt")"
  [ "$(cat "$work/panel.txt")" -lt 80 ]
}
shot_until staff "the staff panel" panel_drawn || fail "no staff panel drawn"
echo "ok: staff chord opens the staff panel"
kill -0 "$app_pid" 2>/dev/null || fail "app died"
echo "PASS"

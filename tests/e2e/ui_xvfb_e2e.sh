#!/bin/bash
# End-to-end check of the ui layer on a real X server: Xvfb (no window manager), the ui driver
# program full-screen, a pointer drag with xdotool, ImageMagick screenshots.
# Checks: the window covers the whole screen; while the button is held the screenshot shows the
# dent at the drag point and the picture everywhere else; after release the picture comes back
# exactly and no frames are drawn at rest; visitor key combinations (Alt-F4, Escape, Ctrl-Q, Ctrl-W, Ctrl-Alt-BackSpace) leave it
# running; the staff chord opens the staff panel.
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
cleanup() {
  [ -n "$app_pid" ] && kill "$app_pid" 2>/dev/null
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null
  wait 2>/dev/null
  # SAS_E2E_KEEP=<dir> keeps the screenshots and the app log for a look.
  [ -n "${SAS_E2E_KEEP:-}" ] && cp "$work"/*.png "$work/app.log" "$SAS_E2E_KEEP"/ 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- app log"; cat "$work/app.log"; exit 1; }

# Xvfb picks a free display number and writes it to fd 3.
Xvfb -displayfd 3 -screen 0 "${width}x${height}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || fail "Xvfb did not start: $(cat "$work/xvfb.log")"
export DISPLAY=":$(cat "$work/display")"
unset WAYLAND_DISPLAY SDL_VIDEODRIVER

"$app" window "$picture" 120 >"$work/app.log" 2>&1 &
app_pid=$!
# Poll rather than sleep: renderer set-up on llvmpipe can take seconds. Wait for the app's
# "ready" first: SDL may replace its first X window by one with an OpenGL visual while it creates
# the renderer, so a window found earlier can vanish.
for _ in $(seq 600); do grep -q '^ready' "$work/app.log" && break; sleep 0.05; done
grep -q '^ready' "$work/app.log" || fail "app never reported ready"
window_id=$(timeout 30 xdotool search --sync --onlyvisible --name '^Sketch-a-Scratch$' | head -1)
[ -n "$window_id" ] || fail "no window appeared"
echo "$(head -1 "$work/app.log")"

eval "$(xdotool getwindowgeometry --shell "$window_id")"
[ "$WIDTH" = "$width" ] && [ "$HEIGHT" = "$height" ] && [ "$X" = 0 ] && [ "$Y" = 0 ] ||
  fail "window is ${WIDTH}x${HEIGHT}+${X}+${Y}, not full-screen ${width}x${height}+0+0"
echo "ok: window covers the screen (${WIDTH}x${HEIGHT})"

# Drag with the button held; xdotool jumps between points, so interpolate the stroke.
x0=400; y0=360; x1=640; y1=420; steps=24
xdotool mousemove $x0 $y0
sleep 0.2
stroke=(mousedown 1)
for i in $(seq 1 $steps); do
  stroke+=(sleep 0.016 mousemove $((x0 + (x1 - x0) * i / steps)) $((y0 + (y1 - y0) * i / steps)))
done
xdotool "${stroke[@]}"  # one xdotool process: even timing at ~60 Hz
sleep 0.15  # let the dent settle under the held tip
import -window root "$work/held.png" || fail "screenshot failed"
grep -q "^down $x0 $y0" "$work/app.log" || fail "no pointer-down at $x0,$y0"
"$app" check "$work/held.png" "$picture" $x1 $y1 || fail "no dent at the drag point in the screenshot"
echo "ok: dent visible at the drag point, picture unchanged elsewhere"
xdotool mouseup 1
sleep 1.2  # release time constant 0.12 s: flat again well within a second
import -window root "$work/released.png" || fail "screenshot failed"
"$app" check "$work/released.png" "$picture" $x1 $y1 >"$work/released.txt"
grep -q "near-dent mean difference 0.00" "$work/released.txt" ||
  fail "picture not restored after release: $(cat "$work/released.txt")"
echo "ok: picture restored after release"

# Redraw only while something changes: at rest the frame counter the app prints every second
# stands still.
last_frames() { grep '^frames' "$work/app.log" | tail -1 | cut -d' ' -f2; }
before=$(last_frames)
sleep 2.2
after=$(last_frames)
[ -n "$before" ] && [ "$before" = "$after" ] || fail "frames drawn while idle ($before -> $after)"
echo "ok: no frames while nothing changes (frame counter stays at $after)"

for combo in alt+F4 Escape ctrl+q ctrl+w ctrl+alt+BackSpace alt+Tab super; do
  xdotool key "$combo"
done
sleep 0.5
kill -0 "$app_pid" 2>/dev/null || fail "a visitor key combination ended the app"
echo "ok: Alt-F4, Escape, Ctrl-Q, Ctrl-W, Ctrl-Alt-BackSpace, Alt-Tab, Super leave it running"

# Staff chord: Ctrl+Alt+S held (0.3 s in the driver program).
xdotool keydown ctrl+alt+s
sleep 0.6
xdotool keyup s alt ctrl
for _ in $(seq 40); do grep -q '^staff open' "$work/app.log" && break; sleep 0.05; done
grep -q '^staff open' "$work/app.log" || fail "staff chord did not open the staff panel"
sleep 0.2
import -window root "$work/staff.png" || fail "screenshot failed"
convert "$work/staff.png" -crop 1x1+$((width / 2))+$((height / 2)) -format '%[fx:int(255*r)]' info: >"$work/panel.txt"
[ "$(cat "$work/panel.txt")" -lt 80 ] || fail "no staff panel drawn (centre red level $(cat "$work/panel.txt"))"
echo "ok: staff chord opens the staff panel"
kill -0 "$app_pid" 2>/dev/null || fail "app died"
echo "PASS"

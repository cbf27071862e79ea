#!/bin/bash
# End-to-end check of the live kiosk on Xvfb (no window manager):
# kiosk_gpio_e2e_app runs the code of `sketch-a-scratch --kiosk` (sas::app::RunKiosk) with the
# GPIO token switches' event source reading "line <offset> falling|rising" from a FIFO this script
# writes, instead of libgpiod (Debian 12's kernel has no gpio-sim); the GPIO switch thread,
# debounce, active-low, line mapping and token rule are the real ones. Its audio goes through
# ALSA's file plugin into FIFOs paced in real time by kiosk_e2e_tool (ALSA_CONFIG_PATH points at a
# config written here); it is driven by xdotool and checked on ImageMagick screenshots, the played
# stream, and the files the app could have written. Checks, in order:
#   full-screen window, switches on GPIO; a 0 ms glitch on token 1's line changes nothing
#   (debounce) while a bouncing falling edge on token 2's line shows broken glass (log line and
#   pixel check against its texture file); a drag with the button held shows the dent at the drag
#   point and the picture elsewhere; the played stream is audible during the drag and silent at
#   its end; a falling edge on token 1's line then shows bubble wrap (the token placed last wins)
#   and its rising edge (token lifted) falls back to broken glass (log lines and pixel checks);
#   key 4 toggles token 4 next to the GPIO switches; lifting token 2 shows the default texture;
#   the record button's line pressed, a countdown, then espeak-ng speech fed as the capture
#   input: the screen shows a grey sound image with silent and sounding rows; visitor key
#   combinations leave it running; the staff chord opens the panel (and closes it); after the
#   idle timeout the voice is wiped and no file the app could write holds any stretch of the
#   speech samples.
# usage: kiosk_xvfb_e2e.sh <kiosk_gpio_e2e_app> <kiosk_e2e_tool> <textures dir>
set -u
app=$(readlink -f "$1")
tool=$(readlink -f "$2")
textures=$3
width=1280
height=720
for t in Xvfb xdotool import espeak-ng; do
  command -v "$t" >/dev/null || { echo "FAIL: $t not installed (install/packages.txt)"; exit 1; }
done
work=$(mktemp -d /tmp/sas-kiosk-e2e-XXXXXX)
xvfb_pid=""
app_pid=""
pacer_pid=""
# stop_pid, and no LeakSanitizer exit scan for Mesa's and D-Bus's blocks (as the other Xvfb tests).
. "$(dirname "${BASH_SOURCE[0]}")/xvfb_common.sh"
# Every wait is bounded. The kiosk goes first, while its X server and audio reader are still there,
# and must stop within 20 s of SIGTERM (systemd's stop does the same); the pacer and Xvfb get 3 s
# and then SIGKILL. A bare `wait` on all three once sat until CTest's 240 s timeout after PASS in
# the sanitizer suite, with nothing saying which one held it.
cleanup() {
  local status=$?
  if [ -n "$app_pid" ] && kill "$app_pid" 2>/dev/null; then
    for _ in $(seq 200); do kill -0 "$app_pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$app_pid" 2>/dev/null; then
      echo "FAIL: the kiosk did not stop within 20 s of SIGTERM: $(ps -o stat=,wchan= -p "$app_pid")"
      kill -9 "$app_pid" 2>/dev/null
      status=1
    fi
    wait "$app_pid" 2>/dev/null
  fi
  [ -n "$pacer_pid" ] && stop_pid "$pacer_pid"
  [ -n "$xvfb_pid" ] && stop_pid "$xvfb_pid"
  [ -n "${SAS_E2E_KEEP:-}" ] && cp "$work"/*.png "$work/app.log" "$SAS_E2E_KEEP"/ 2>/dev/null
  rm -rf "$work"
  exit "$status"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- app log"; grep -v 'jack server\|JackShm\|Cannot connect' "$work/app.log"; exit 1; }
wait_count() {  # wait_count <pattern> <count> <tenths of a second>: the log has count such lines
  for _ in $(seq "$3"); do
    [ "$(grep -c "$1" "$work/app.log")" -ge "$2" ] && return 0
    [ -n "$app_pid" ] && ! kill -0 "$app_pid" 2>/dev/null && return 1
    sleep 0.1
  done
  return 1
}
wait_log() { wait_count "$1" 1 "$2"; }  # wait_log <pattern> <tenths of a second>
# The fake GPIO chip: one edge per argument, all in one write (so one read, microseconds apart).
gpio() { printf '%s\n' "$@" >&4 || fail "cannot write the GPIO FIFO"; }
matches() {  # matches <shot> <texture>: the screenshot shows that texture's picture, not another
  local others=()
  for t in bubble_wrap wooden_board broken_glass cracked_ground; do
    [ "$t" = "$2" ] || others+=("$textures/$t/picture.png")
  done
  "$tool" matches "$work/$1.png" "$textures/$2/picture.png" "${others[@]}"
}
shot() { import -window root "$work/$1.png" || fail "screenshot $1 failed"; }

mkdir -p "$work/state" "$work/home" "$work/cwd"
# The visitor's voice for the capture input: espeak-ng speech as float32 mono 48 kHz.
espeak-ng -w "$work/speech.wav" "Hello museum, this is my voice, scratch it" 2>/dev/null ||
  fail "espeak-ng could not speak"
"$tool" speech "$work/speech.wav" "$work/speech.f32" || fail "speech conversion"
mkfifo "$work/out.fifo" "$work/in.fifo" "$work/gpio.fifo"
"$tool" pace "$work/out.fifo" "$work/out.raw" "$work/in.fifo" "$work/speech.f32" "$work/speak" &
pacer_pid=$!
cat >"$work/asound.conf" <<EOF
pcm.null { type null }
pcm.kiosk_out { type file slave.pcm "null" file "$work/out.fifo" format "raw" }
pcm.kiosk_in { type file slave.pcm "null" file "/dev/null" infile "$work/in.fifo" format "raw" }
pcm.!default { type asym playback.pcm "kiosk_out" capture.pcm "kiosk_in" }
EOF
cat >"$work/kiosk.toml" <<EOF
[session]
idle_timeout_s = 8.0
[switches]
backend = "gpio"
# Not the default offsets, so the edges only arrive if the configured lines are mapped.
gpio_lines = ["5", "6", "13", "19", "26"]
EOF
cp "$work/kiosk.toml" "$work/kiosk.toml.before"

Xvfb -displayfd 3 -screen 0 "${width}x${height}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || fail "Xvfb did not start"
export DISPLAY=":$(cat "$work/display")"
unset WAYLAND_DISPLAY SDL_VIDEODRIVER XDG_STATE_HOME STATE_DIRECTORY

touch "$work/start.stamp"
(cd "$work/cwd" && HOME="$work/home" ALSA_CONFIG_PATH="$work/asound.conf" \
  exec "$app" --gpio-fifo "$work/gpio.fifo" --config "$work/kiosk.toml" \
  --state-dir "$work/state") >"$work/app.log" 2>&1 &
app_pid=$!
# Held open read-write: a write never blocks, even when the kiosk is gone.
exec 4<>"$work/gpio.fifo"
wait_log '^kiosk ready' 300 || fail "the kiosk never reported ready"
grep '^kiosk ready' "$work/app.log"
grep -q '^kiosk ready.*switches gpio$' "$work/app.log" || fail "the token switches are not on GPIO"
window_id=$(timeout 30 xdotool search --sync --onlyvisible --name '^Sketch-a-Scratch$' | head -1)
[ -n "$window_id" ] || fail "no window appeared"
eval "$(xdotool getwindowgeometry --shell "$window_id")"
[ "$WIDTH" = "$width" ] && [ "$HEIGHT" = "$height" ] && [ "$X" = 0 ] && [ "$Y" = 0 ] ||
  fail "window is ${WIDTH}x${HEIGHT}+${X}+${Y}, not full-screen"
echo "ok: full-screen ${WIDTH}x${HEIGHT}"
grep -q 'audio running' "$work/app.log" || fail "the audio device did not open"
for _ in $(seq 50); do [ -s "$work/out.raw" ] && break; sleep 0.1; done
[ -s "$work/out.raw" ] || fail "nothing is played"

# A visit starts: a first touch leaves the attract screen.
xdotool mousemove 100 100 click 1
wait_log 'visit started' 30 || fail "a touch did not leave the attract screen"
sleep 0.8  # the attract veil fades out with the picture's next frame

# A glitch on token 1's line (low and back within the debounce time) and a token placed on
# switch 2 whose contact bounces: broken glass, a loud texture, replaces the default.
gpio "line 5 falling" "line 5 rising" "line 6 falling" "line 6 rising" "line 6 falling"
wait_log 'showing broken_glass' 30 || fail "a falling edge on token 2's line did not switch the texture"
sleep 1.0  # cross-fade 0.45 s
grep -q 'showing bubble_wrap' "$work/app.log" && fail "a glitch shorter than the debounce time placed token 1"
shot glass
matches glass broken_glass || fail "the screen does not show broken glass"
echo "ok: GPIO token 2 shows broken glass (pixel check), the glitch on token 1 was debounced away"

# Drag with the button held across it.
x0=400; y0=360; x1=760; y1=420; steps=40
xdotool mousemove $x0 $y0
sleep 0.2
down=$(stat -c %s "$work/out.raw")
stroke=(mousedown 1)
for i in $(seq 1 $steps); do
  stroke+=(sleep 0.02 mousemove $((x0 + (x1 - x0) * i / steps)) $((y0 + (y1 - y0) * i / steps)))
done
xdotool "${stroke[@]}"
sleep 0.15
shot held
up=$(stat -c %s "$work/out.raw")
xdotool mouseup 1
"$tool" dent "$work/held.png" "$textures/broken_glass/picture.png" $x1 $y1 ||
  fail "no dent at the drag point"
echo "ok: dent at the drag point, picture elsewhere"
sleep 3.0
"$tool" audio "$work/out.raw" "$down" "$up" || fail "audio during/after the drag"
echo "ok: audible during the drag, silent after the release"

# A second token, on switch 1: bubble wrap (the token placed last wins).
gpio "line 5 falling"
wait_log 'showing bubble_wrap' 30 || fail "a falling edge on token 1's line did not switch the texture"
sleep 1.0
shot token
matches token bubble_wrap || fail "the screen does not show bubble wrap"
echo "ok: GPIO token 1 placed last shows bubble wrap (pixel check against its texture file)"
# Lifted: back to the token still on its switch.
gpio "line 5 rising"
wait_count 'showing broken_glass' 2 30 || fail "lifting token 1 did not fall back to token 2"
sleep 1.0
shot lifted
matches lifted broken_glass || fail "the screen does not show broken glass after the lift"
echo "ok: lifting GPIO token 1 falls back to token 2, broken glass (pixel check)"
# The keys still work next to the GPIO switches (staff, tests): key 4 places and lifts token 4.
xdotool key 4
wait_log 'showing cracked_ground' 30 || fail "token key 4 did not switch the texture"
xdotool key 4
wait_count 'showing broken_glass' 3 30 || fail "token key 4 lifted did not fall back to token 2"
defaults=$(grep -c 'showing wooden_board' "$work/app.log")
gpio "line 6 rising"
wait_count 'showing wooden_board' $((defaults + 1)) 30 || fail "with no token left the default texture is not shown"
echo "ok: key 4 toggles token 4 next to GPIO, no token left shows the default texture"

# The voice: the record button's line, countdown, then the speech arrives at the microphone.
gpio "line 26 falling"
sleep 0.1
gpio "line 26 rising"
wait_log 'recording started' 60 || fail "the record button's GPIO line did not start a recording"
echo "ok: the record button's GPIO line starts the recording"
touch "$work/speak"
wait_log 'showing the voice' 90 || fail "the recording did not become the surface"
sleep 1.0
shot voice
"$tool" voice "$work/voice.png" || fail "the screen does not show the recording's sound image"
echo "ok: the recorded speech is the surface"

for combo in alt+F4 Escape ctrl+q ctrl+w ctrl+alt+BackSpace alt+Tab; do xdotool key "$combo"; done
sleep 0.5
kill -0 "$app_pid" 2>/dev/null || fail "a visitor key combination ended the kiosk"
echo "ok: Alt-F4, Escape, Ctrl-Q, Ctrl-W, Ctrl-Alt-BackSpace, Alt-Tab leave it running"

xdotool keydown ctrl+alt+s
sleep 1.3  # the chord must be held 1 s
xdotool keyup s alt ctrl
wait_log 'staff panel opened' 30 || fail "the staff chord did not open the panel"
sleep 0.5
shot staff
# The mean over the middle 40x40 pixels: the panel's text runs across it, the dark plate dominates.
convert "$work/staff.png" -crop 40x40+$((width / 2 - 20))+$((height / 2 - 20)) +repage \
  -format '%[fx:int(255*mean.r)]' info: >"$work/panel.txt"
[ "$(cat "$work/panel.txt")" -lt 90 ] || fail "no staff panel drawn"
echo "ok: staff chord opens the staff panel"
# The panel's "Volume +" (the fifth of seven buttons along its bottom edge, live_kiosk.cpp's
# StaffButtonRects): one step up, applied and kept in the state folder, not in the config file.
panel_w=$((width * 4 / 5)); panel_h=$((height * 21 / 25))
button_w=$(( (panel_w - 8 * 12) / 7 )); [ "$button_w" -gt 200 ] && button_w=200
volume_up_x=$(( (width - panel_w) / 2 + 12 + 4 * (12 + button_w) + button_w / 2 ))
volume_up_y=$(( (height - panel_h) / 2 + panel_h - 12 - 22 ))
xdotool mousemove "$volume_up_x" "$volume_up_y" click 1
wait_log 'staff: volume 3 dB, vibration 0 dB' 30 || fail "the panel's Volume + did not step the volume"
grep -qx 'volume_db = 3.0' "$work/state/staff.toml" || fail "the volume step was not kept in staff.toml"
cmp -s "$work/kiosk.toml.before" "$work/kiosk.toml" || fail "the staff's configuration file was rewritten"
echo "ok: the panel's Volume + steps the volume and keeps it in the state folder"
xdotool keydown ctrl+alt+s
sleep 1.3
xdotool keyup s alt ctrl
wait_log 'staff panel closed' 30 || fail "the staff chord did not close the panel"

# Idle: after 8 s without activity the voice is wiped.
wait_log 'voice wiped' 150 || fail "the idle reset did not wipe the voice"
echo "ok: idle reset wiped the voice"
kill -0 "$app_pid" 2>/dev/null || fail "kiosk died"
# Everything the app could have written since it started: none holds the voice.
mapfile -t written < <(find "$work/state" "$work/home" "$work/cwd" /tmp /var/tmp /dev/shm -xdev \
  -type f -newer "$work/start.stamp" -size -64M 2>/dev/null |
  grep -v -e "^/tmp/sas-kiosk-e2e-[^/]*/[^/]*\$")  # the test's own inputs and outputs (any run)
"$tool" find "$work/speech.f32" "${written[@]}" || fail "a file holds the visitor's voice"
ls "$work/state"
echo "PASS"

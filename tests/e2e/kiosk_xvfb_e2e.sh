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
#   speech samples. The language key (at the start) and the record key (after the idle reset),
#   each pressed during the attract screen's passive stroke, leave no stroke in the played stream
#   0.5 s later.
# Every step waits for its event (a log line, a screenshot that passes its check, the played
# stream's length) with xvfb_common.sh's generous deadline, and says how long it waited.
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
    local t0
    t0=$(now_ms)
    for _ in $(seq 200); do kill -0 "$app_pid" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$app_pid" 2>/dev/null || echo "the kiosk stopped $(seconds_since "$t0") s after SIGTERM"
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
log_has() {  # log_has <pattern> [count]: the app's log has at least count such lines
  local n
  n=$(grep -c -- "$1" "$work/app.log" 2>/dev/null)
  [ "${n:-0}" -ge "${2:-1}" ]
}
wait_count() { until_true "log: $1 (x$2)" log_has "$1" "$2"; }  # wait_count <pattern> <count>
wait_log() { until_true "log: $1" log_has "$1"; }                # wait_log <pattern>
# The fake GPIO chip: one edge per argument, all in one write (so one read, microseconds apart).
gpio() { printf '%s\n' "$@" >&4 || fail "cannot write the GPIO FIFO"; }
matches() {  # matches <shot> <texture>: the screenshot shows that texture's picture, not another
  local others=()
  for t in bubble_wrap wooden_board broken_glass cracked_ground; do
    [ "$t" = "$2" ] || others+=("$textures/$t/picture.png")
  done
  "$tool" matches "$work/$1.png" "$textures/$2/picture.png" "${others[@]}"
}
# The staff panel's dark plate dominates the mean over the middle 40x40 pixels (its text runs
# across them).
panel_drawn() {
  convert "$work/staff.png" -crop 40x40+$((width / 2 - 20))+$((height / 2 - 20)) +repage \
    -format '%[fx:int(255*mean.r)]' info: >"$work/panel.txt" || return 1
  echo "panel: mean red $(cat "$work/panel.txt") in the middle"
  [ "$(cat "$work/panel.txt")" -lt 90 ]
}
# The dent has sprung back: the dent check's figures show the picture near the drag's end as well
# as far from it (the kiosk has handled the release).
undented() {
  local figures
  figures=$("$tool" dent "$work/released.png" "$textures/broken_glass/picture.png" $x1 $y1)
  echo "$figures"
  awk '/^dent:/ { ok = ($5 + 0 <= 6.0 && $7 + 0 < 2.0) } END { exit !ok }' <<<"$figures"
}
# The played stream (float32 stereo at 48 kHz: 384000 bytes a second) is at least this long.
stream_bytes() { stat -c %s "$work/out.raw"; }
stream_reached() { [ "$(stream_bytes)" -ge "$1" ]; }
# The attract screen's passive stroke is felt now: the vibration (channel 2) of the stream's last
# 0.2 s.
stroke_felt() {
  local b
  b=$(stream_bytes)
  "$tool" level "$work/out.raw" 2 $((b - 76800)) "$b" -60 0 >/dev/null
}
# passive_lifted <what> <xdotool args...>: during a passive stroke the keys end the attract screen;
# from 0.5 to 1 s later the stream carries no stroke. Judged on the vibration (channel 2), which
# only a stroke drives: the cue the key starts is spoken on channel 1.
passive_lifted() {
  local what=$1 n at
  shift
  until_true "the passive stroke felt" stroke_felt || fail "no passive stroke on the attract screen"
  n=$(grep -c 'visit started' "$work/app.log")
  xdotool "$@"
  wait_count 'visit started' $((n + 1)) || fail "$what did not end the attract screen"
  at=$(stream_bytes)
  until_true "1 s of the stream after $what" stream_reached $((at + 384000)) ||
    fail "the stream stopped after $what"
  "$tool" level "$work/out.raw" 2 $((at + 192000)) $((at + 384000)) -999 -70 ||
    fail "the passive stroke goes on after $what"
  echo "ok: $what during the passive stroke lifts it: no stroke 0.5 s later"
}

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
# Long enough for the voice's screenshot on a busy machine: the idle reset wipes the voice this
# long after the recording ended.
idle_timeout_s = 20.0
# No spoken description while the pen rests: it rests at the drag's end until a screenshot shows
# the dent, and a description started then would still be playing when the stream must have
# decayed after the release.
describe_after_rest_s = 0.0
[switches]
backend = "gpio"
# Not the default offsets, so the edges only arrive if the configured lines are mapped.
gpio_lines = ["5", "6", "13", "19", "26"]
EOF
cp "$work/kiosk.toml" "$work/kiosk.toml.before"

start_xvfb "$width" "$height" || fail "Xvfb did not start"
unset WAYLAND_DISPLAY SDL_VIDEODRIVER XDG_STATE_HOME STATE_DIRECTORY

touch "$work/start.stamp"
(cd "$work/cwd" && HOME="$work/home" ALSA_CONFIG_PATH="$work/asound.conf" \
  exec "$app" --gpio-fifo "$work/gpio.fifo" --config "$work/kiosk.toml" \
  --state-dir "$work/state") >"$work/app.log" 2>&1 &
app_pid=$!
watch=$app_pid  # a wait ends at once when the kiosk is gone
# Held open read-write: a write never blocks, even when the kiosk is gone.
exec 4<>"$work/gpio.fifo"
wait_log '^kiosk ready' || fail "the kiosk never reported ready"
grep '^kiosk ready' "$work/app.log"
grep -q '^kiosk ready.*switches gpio$' "$work/app.log" || fail "the token switches are not on GPIO"
window_id=$(timeout "$e2e_wait_s" xdotool search --sync --onlyvisible --name '^Sketch-a-Scratch$' | head -1)
[ -n "$window_id" ] || fail "no window appeared"
eval "$(xdotool getwindowgeometry --shell "$window_id")"
[ "$WIDTH" = "$width" ] && [ "$HEIGHT" = "$height" ] && [ "$X" = 0 ] && [ "$Y" = 0 ] ||
  fail "window is ${WIDTH}x${HEIGHT}+${X}+${Y}, not full-screen"
echo "ok: full-screen ${WIDTH}x${HEIGHT}"
grep -q 'audio running' "$work/app.log" || fail "the audio device did not open"
until_true "the played stream" test -s "$work/out.raw" || fail "nothing is played"

# The language key during the attract screen's passive stroke (the first burst starts 6 s after
# the attract screen) ends the stroke with the attract screen.
passive_lifted "the language key" key l

# A visit starts: a first touch leaves the attract screen.
xdotool mousemove 100 100 click 1
wait_log 'visit started' || fail "a touch did not leave the attract screen"

# A glitch on token 1's line (low and back within the debounce time) and a token placed on
# switch 2 whose contact bounces: broken glass, a loud texture, replaces the default.
gpio "line 5 falling" "line 5 rising" "line 6 falling" "line 6 rising" "line 6 falling"
wait_log 'showing broken_glass' || fail "a falling edge on token 2's line did not switch the texture"
# The attract veil fades out and the pictures cross-fade (0.45 s) after the log line.
shot_until glass "broken glass" matches glass broken_glass || fail "the screen does not show broken glass"
# The switch thread hands on edges in time order, so a glitch let through would have been logged
# before broken glass; it is looked for once the screen shows broken glass, later still.
grep -q 'showing bubble_wrap' "$work/app.log" && fail "a glitch shorter than the debounce time placed token 1"
echo "ok: GPIO token 2 shows broken glass (pixel check), the glitch on token 1 was debounced away"

# Drag with the button held across it.
x0=400; y0=360; x1=760; y1=420; steps=40
xdotool mousemove $x0 $y0
sleep 0.2  # part of the gesture: the pointer rests at the start before the button goes down
down=$(stream_bytes)
stroke=(mousedown 1)
for i in $(seq 1 $steps); do
  stroke+=(sleep 0.02 mousemove $((x0 + (x1 - x0) * i / steps)) $((y0 + (y1 - y0) * i / steps)))
done
xdotool "${stroke[@]}"
# The button stays down until a screenshot shows the dent under the drag's end.
shot_until held "the dent at the drag point" \
  "$tool" dent "$work/held.png" "$textures/broken_glass/picture.png" $x1 $y1 ||
  fail "no dent at the drag point"
# The kiosk has drawn the whole drag, so the stream holds its sound up to here (the audio check
# allows for the few buffers it runs ahead of the pacer).
up=$(stream_bytes)
xdotool mouseup 1
released=$(stream_bytes)
echo "ok: dent at the drag point, picture elsewhere"
# The stream up to 3 s after the release (by its length: the pacer plays it in real time), once
# the kiosk has handled the release (its dent sprung back on the screen): its end must have
# decayed to silence. Cut there, it is judged at the same point however long the waits took.
shot_until released "the dent sprung back after the release" undented ||
  fail "the dent did not spring back after the release"
until_true "3 s of the stream after the release" stream_reached $((released + 3 * 384000)) ||
  fail "the stream stopped after the release"
head -c $(((released + 3 * 384000) / 8 * 8)) "$work/out.raw" >"$work/drag.raw"
"$tool" audio "$work/drag.raw" "$down" "$up" || fail "audio during/after the drag"
echo "ok: audible during the drag, silent after the release"

# A second token, on switch 1: bubble wrap (the token placed last wins).
gpio "line 5 falling"
wait_log 'showing bubble_wrap' || fail "a falling edge on token 1's line did not switch the texture"
shot_until token "bubble wrap" matches token bubble_wrap || fail "the screen does not show bubble wrap"
echo "ok: GPIO token 1 placed last shows bubble wrap (pixel check against its texture file)"
# Lifted: back to the token still on its switch.
gpio "line 5 rising"
wait_count 'showing broken_glass' 2 || fail "lifting token 1 did not fall back to token 2"
shot_until lifted "broken glass" matches lifted broken_glass ||
  fail "the screen does not show broken glass after the lift"
echo "ok: lifting GPIO token 1 falls back to token 2, broken glass (pixel check)"
# The keys still work next to the GPIO switches (staff, tests): key 4 places and lifts token 4.
xdotool key 4
wait_log 'showing cracked_ground' || fail "token key 4 did not switch the texture"
xdotool key 4
wait_count 'showing broken_glass' 3 || fail "token key 4 lifted did not fall back to token 2"
defaults=$(grep -c 'showing wooden_board' "$work/app.log")
gpio "line 6 rising"
wait_count 'showing wooden_board' $((defaults + 1)) || fail "with no token left the default texture is not shown"
echo "ok: key 4 toggles token 4 next to GPIO, no token left shows the default texture"

# The voice: the record button's line, countdown, then the speech arrives at the microphone.
# The fake chip stamps an edge when the switch thread reads it: the press is timed from the read of
# the falling edge. 0.3 s is the press itself: past the 30 ms debounce, well short of the 1.2 s
# hold that cancels the recording.
gpio "line 26 falling"
wait_log 'fake gpio: line 26 (record) falling' || fail "the record button's falling edge was not read"
sleep 0.3
gpio "line 26 rising"
recording_decided() { log_has 'recording started' || log_has 'recording cancelled'; }
until_true "log: recording started (after the countdown)" recording_decided &&
  log_has 'recording started' || fail "the record button's GPIO line did not start a recording"
echo "ok: the record button's GPIO line starts the recording"
touch "$work/speak"
wait_log 'showing the voice' || fail "the recording did not become the surface"
shot_until voice "the recording's sound image" "$tool" voice "$work/voice.png" ||
  fail "the screen does not show the recording's sound image$(log_has 'voice wiped' &&
    echo ' (the idle reset wiped it first)')"
echo "ok: the recorded speech is the surface"

for combo in alt+F4 Escape ctrl+q ctrl+w ctrl+alt+BackSpace alt+Tab; do xdotool key "$combo"; done
# The staff chord (held until the kiosk says the panel opened: it must be held 1 s by the kiosk's
# own clock) comes after the combinations in the one event queue: once it is handled they were,
# and the kiosk still runs.
xdotool keydown ctrl+alt+s
wait_log 'staff panel opened'
opened=$?
xdotool keyup s alt ctrl
kill -0 "$app_pid" 2>/dev/null || fail "a visitor key combination ended the kiosk"
[ $opened = 0 ] || fail "the staff chord did not open the panel"
echo "ok: Alt-F4, Escape, Ctrl-Q, Ctrl-W, Ctrl-Alt-BackSpace, Alt-Tab leave it running"
shot_until staff "the staff panel" panel_drawn || fail "no staff panel drawn"
echo "ok: staff chord opens the staff panel"
# The panel's "Volume +" (the fifth of seven buttons along its bottom edge, live_kiosk.cpp's
# StaffButtonRects): one step up, applied and kept in the state folder, not in the config file.
panel_w=$((width * 4 / 5)); panel_h=$((height * 21 / 25))
button_w=$(( (panel_w - 8 * 12) / 7 )); [ "$button_w" -gt 200 ] && button_w=200
volume_up_x=$(( (width - panel_w) / 2 + 12 + 4 * (12 + button_w) + button_w / 2 ))
volume_up_y=$(( (height - panel_h) / 2 + panel_h - 12 - 22 ))
xdotool mousemove "$volume_up_x" "$volume_up_y" click 1
wait_log 'staff: volume 3 dB, vibration 0 dB' || fail "the panel's Volume + did not step the volume"
grep -qx 'volume_db = 3.0' "$work/state/staff.toml" || fail "the volume step was not kept in staff.toml"
cmp -s "$work/kiosk.toml.before" "$work/kiosk.toml" || fail "the staff's configuration file was rewritten"
echo "ok: the panel's Volume + steps the volume and keeps it in the state folder"
xdotool keydown ctrl+alt+s
wait_log 'staff panel closed'
closed=$?
xdotool keyup s alt ctrl
[ $closed = 0 ] || fail "the staff chord did not close the panel"

# Idle: idle_timeout_s after the last activity (the chord) the voice is wiped.
wait_log 'voice wiped' || fail "the idle reset did not wipe the voice"
echo "ok: idle reset wiped the voice"
kill -0 "$app_pid" 2>/dev/null || fail "kiosk died"
# Everything the app could have written since it started: none holds the voice.
mapfile -t written < <(find "$work/state" "$work/home" "$work/cwd" /tmp /var/tmp /dev/shm -xdev \
  -type f -newer "$work/start.stamp" -size -64M 2>/dev/null |
  grep -v -e "^/tmp/sas-kiosk-e2e-[^/]*/[^/]*\$")  # the test's own inputs and outputs (any run)
"$tool" find "$work/speech.f32" "${written[@]}" || fail "a file holds the visitor's voice"
ls "$work/state"
# Back on the attract screen: the record key during its passive stroke ends the stroke too (a
# press and release, not the hold that cancels).
passive_lifted "the record key" key r
echo "PASS"

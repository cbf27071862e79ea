#!/bin/bash
# End-to-end check of the real kiosk (issue 7, acceptance 1-3): `sketch-a-scratch --kiosk` on
# Xvfb (no window manager), its audio through ALSA's file plugin into FIFOs paced in real time by
# kiosk_e2e_tool (ALSA_CONFIG_PATH points at a config written here), driven by xdotool, checked
# on ImageMagick screenshots, the played stream, and the files the app could have written.
# Checks, in order:
#   full-screen window; token key 2 shows broken glass; a drag with the button held shows the
#   dent at the drag point and the picture elsewhere; the played stream is audible during the drag
#   and silent at its end; token key 1 then shows bubble wrap (pixel check against its texture
#   file); the record key, a
#   countdown, then espeak-ng speech fed as the capture input: the screen shows a grey sound
#   image with silent and sounding rows; visitor key combinations leave it running; the staff
#   chord opens the panel (and closes it); after the idle timeout the voice is wiped and no file
#   the app could write holds any stretch of the speech samples.
# usage: kiosk_xvfb_e2e.sh <sketch-a-scratch> <kiosk_e2e_tool> <textures dir>
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
cleanup() {
  [ -n "$app_pid" ] && kill "$app_pid" 2>/dev/null
  [ -n "$pacer_pid" ] && kill "$pacer_pid" 2>/dev/null
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null
  wait 2>/dev/null
  [ -n "${SAS_E2E_KEEP:-}" ] && cp "$work"/*.png "$work/app.log" "$SAS_E2E_KEEP"/ 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- app log"; grep -v 'jack server\|JackShm\|Cannot connect' "$work/app.log"; exit 1; }
wait_log() {  # wait_log <pattern> <tenths of a second>
  for _ in $(seq "$2"); do
    grep -q "$1" "$work/app.log" && return 0
    [ -n "$app_pid" ] && ! kill -0 "$app_pid" 2>/dev/null && return 1
    sleep 0.1
  done
  return 1
}
shot() { import -window root "$work/$1.png" || fail "screenshot $1 failed"; }

mkdir -p "$work/state" "$work/home" "$work/cwd"
# The visitor's voice for the capture input: espeak-ng speech as float32 mono 48 kHz.
espeak-ng -w "$work/speech.wav" "Hello museum, this is my voice, scratch it" 2>/dev/null ||
  fail "espeak-ng could not speak"
"$tool" speech "$work/speech.wav" "$work/speech.f32" || fail "speech conversion"
mkfifo "$work/out.fifo" "$work/in.fifo"
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
backend = "keyboard"
EOF

Xvfb -displayfd 3 -screen 0 "${width}x${height}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || fail "Xvfb did not start"
export DISPLAY=":$(cat "$work/display")"
unset WAYLAND_DISPLAY SDL_VIDEODRIVER XDG_STATE_HOME STATE_DIRECTORY

touch "$work/start.stamp"
(cd "$work/cwd" && HOME="$work/home" ALSA_CONFIG_PATH="$work/asound.conf" \
  exec "$app" --kiosk --config "$work/kiosk.toml" --state-dir "$work/state") >"$work/app.log" 2>&1 &
app_pid=$!
wait_log '^kiosk ready' 300 || fail "the kiosk never reported ready"
grep '^kiosk ready' "$work/app.log"
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

# A token on switch 2 (keyboard stand-in): broken glass, a loud texture, replaces the default.
xdotool key 2
wait_log 'showing broken_glass' 30 || fail "token key 2 did not switch the texture"
sleep 1.0  # cross-fade 0.45 s

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
xdotool key 1
wait_log 'showing bubble_wrap' 30 || fail "token key 1 did not switch the texture"
sleep 1.0
shot token
"$tool" matches "$work/token.png" "$textures/bubble_wrap/picture.png" \
  "$textures/wooden_board/picture.png" "$textures/broken_glass/picture.png" \
  "$textures/cracked_ground/picture.png" || fail "the screen does not show bubble wrap"
echo "ok: token switch shows bubble wrap (pixel check against its texture file)"

# The voice: record key, countdown, then the speech arrives at the microphone.
xdotool keydown r
sleep 0.1
xdotool keyup r
wait_log 'recording started' 60 || fail "recording never started"
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
convert "$work/staff.png" -crop 1x1+$((width / 2))+$((height / 2)) -format '%[fx:int(255*r)]' info: >"$work/panel.txt"
[ "$(cat "$work/panel.txt")" -lt 90 ] || fail "no staff panel drawn"
echo "ok: staff chord opens the staff panel"
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

#!/bin/bash
# The UI latency while the audio device is gone (docs/engineering.md, "Reliability"): runs ui_latency_audio_loss
# (the live kiosk's code with a fake audio device removed for 10 s, every reopen hanging 3 s) under
# Xvfb while xdotool draws strokes on it the whole time, and lets the tool write its report.
# A measurement, run by hand (never by CTest):
#   tests/bench/ui_latency_audio_loss.sh build/tests/bench/ui_latency_audio_loss docs/ui-latency-audio-loss.md
# Exit status: the tool's (0 when the longest gap during the loss is within 100 ms).
set -u
tool=$(readlink -f "$1")
docs=$(readlink -f "$2")
for t in Xvfb xdotool; do
  command -v "$t" >/dev/null || { echo "FAIL: $t not installed (install/packages.txt)"; exit 1; }
done
work=$(mktemp -d /tmp/sas-ui-latency-XXXXXX)
xvfb_pid=""
tool_pid=""
cleanup() {
  [ -n "$tool_pid" ] && kill -9 "$tool_pid" 2>/dev/null
  [ -n "$xvfb_pid" ] && kill "$xvfb_pid" 2>/dev/null
  wait 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT
mkdir -p "$work/state" "$work/home"
# The microphone goes through PortAudio still: point ALSA at a card that does not exist.
echo 'pcm.!default { type hw card 63 }' >"$work/asound.conf"
cat >"$work/kiosk.toml" <<EOF2
[session]
idle_timeout_s = 60.0
[switches]
backend = "keyboard"
EOF2
Xvfb -displayfd 3 -screen 0 1280x720x24 -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || { echo "FAIL: Xvfb did not start"; exit 1; }
export DISPLAY=":$(cat "$work/display")"
unset WAYLAND_DISPLAY SDL_VIDEODRIVER XDG_STATE_HOME STATE_DIRECTORY
commit=$(git -C "$(dirname "$0")" rev-parse --short HEAD 2>/dev/null || echo unknown)
(cd "$work" && HOME="$work/home" ALSA_CONFIG_PATH="$work/asound.conf" \
  exec "$tool" --config "$work/kiosk.toml" --state-dir "$work/state" --docs "$docs" \
  --note "built at commit $commit") >"$work/tool.log" 2>&1 &
tool_pid=$!
for _ in $(seq 300); do grep -q '^kiosk ready' "$work/tool.log" && break; sleep 0.1; done
grep -q '^kiosk ready' "$work/tool.log" || { echo "FAIL: the kiosk never came up"; cat "$work/tool.log"; exit 1; }
# A visitor drawing the whole time: strokes back and forth across the picture.
while kill -0 "$tool_pid" 2>/dev/null; do
  xdotool mousemove 300 300 mousedown 1 2>/dev/null
  for x in $(seq 320 40 980); do xdotool mousemove "$x" $((300 + (x % 160))) 2>/dev/null; done
  xdotool mouseup 1 2>/dev/null
done
wait "$tool_pid"
status=$?
tool_pid=""
grep -v 'jack server\|JackShm\|Cannot connect' "$work/tool.log" | grep -i 'audio_out\|during the loss\|error' 
exit $status

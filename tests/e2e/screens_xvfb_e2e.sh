#!/usr/bin/env bash
# The visitor's screens on a real X server at one size: Xvfb at <width>x<height>, then the screens
# test (tests/ui/test_visitor_screens.cpp) drawing each screen through the kiosk's own full-screen
# window and reading the pixels back: what it says (the language table's sentences), the plates'
# contrast (>= 7:1) and that the window shows what the software composition shows.
# SAS_SCREENSHOTS_DIR (optional) receives the screenshots.
#   screens_xvfb_e2e.sh <screens_tests> <width> <height>
set -euo pipefail
tests="$1"
width="$2"
height="$3"
command -v Xvfb >/dev/null || { echo "SKIP: Xvfb not installed (install/packages.txt, test)"; exit 77; }
work=$(mktemp -d /tmp/sas-screens-XXXXXX)
. "$(dirname "${BASH_SOURCE[0]}")/xvfb_common.sh"
cleanup() {
  [ -n "${xvfb_pid:-}" ] && stop_pid "$xvfb_pid"
  rm -rf "$work"
}
trap cleanup EXIT
# Xvfb picks a free display number and writes it to fd 3.
Xvfb -displayfd 3 -screen 0 "${width}x${height}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
xvfb_pid=$!
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.05; done
[ -s "$work/display" ] || { echo "FAIL: Xvfb did not start: $(cat "$work/xvfb.log")"; exit 1; }
export DISPLAY=":$(cat "$work/display")"
unset WAYLAND_DISPLAY
export SDL_VIDEODRIVER=x11
SAS_SCREENS_WINDOW=1 "$tests" "visitor screens*"

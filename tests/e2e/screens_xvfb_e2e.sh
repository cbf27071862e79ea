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
# Waits for Xvfb's display number (xvfb_common.sh's generous deadline); the screens test itself
# reads back each frame it presents, so nothing here waits on the screen.
start_xvfb "$width" "$height" || { echo "FAIL: Xvfb did not start"; exit 1; }
unset WAYLAND_DISPLAY
export SDL_VIDEODRIVER=x11
SAS_SCREENS_WINDOW=1 "$tests" "visitor screens*"

#!/usr/bin/env bash
# Re-makes every screenshot in docs/screenshots/ (README: "What visitors meet", Documentation):
# the visitor's screens (attract, exploring, countdown, recording, voice) through the screens
# test, and the live kiosk's staff panel, each on Xvfb at 1920x1080 and 1280x720. Needs a built
# tree (the screens_tests and sketch-a-scratch targets) and the test packages (Xvfb, xdotool,
# ImageMagick; install/packages.txt).
#   tests/e2e/make_screenshots.sh [build dir, default build]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$root/build}" && pwd)"
out="$root/docs/screenshots"
mkdir -p "$out"
for size in 1920x1080 1280x720; do
  w=${size%x*}
  h=${size#*x}
  SAS_SCREENSHOTS_DIR="$out" "$here/screens_xvfb_e2e.sh" "$build/tests/ui/screens_tests" "$w" "$h"
  "$here/staff_panel_screenshot.sh" "$build/app/sketch-a-scratch" "$w" "$h" \
    "$out/staff-panel-$size.jpg"
done
ls -l "$out"

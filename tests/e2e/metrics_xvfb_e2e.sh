#!/usr/bin/env bash
# The health metrics file the live kiosk writes, as node-exporter's textfile collector will read
# it: the kiosk binary under Xvfb (keyboard switches, no sound card) with the shipped example
# configuration and a box name that needs escaping; once the file is in the state folder,
# Prometheus's own linter (`promtool check metrics`, Debian's prometheus package) must accept it,
# it names the box and the textures, and no temporary is left beside it. Each step waits for its
# event (the file, the kiosk's log line) with xvfb_common.sh's generous deadline.
#   metrics_xvfb_e2e.sh <sketch-a-scratch> <kiosk.toml>
set -euo pipefail
app=$(readlink -f "$1")
example=$(readlink -f "$2")
for t in Xvfb promtool; do
  command -v "$t" >/dev/null || { echo "FAIL: $t not installed (install/packages.txt, test group)"; exit 1; }
done
work=$(mktemp -d /tmp/sas-metrics-e2e-XXXXXX)
. "$(dirname "${BASH_SOURCE[0]}")/xvfb_common.sh"
cleanup() {
  [ -n "${app_pid:-}" ] && stop_pid "$app_pid"
  [ -n "${xvfb_pid:-}" ] && stop_pid "$xvfb_pid"
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- kiosk log"; cat "$work/app.log" 2>/dev/null; exit 1; }
mkdir -p "$work/state"
config="$work/kiosk.toml"
# The shipped configuration, with the keyboard for tokens and a box name with a quote and a
# backslash (the label's escaping is what the linter reads).
sed -e 's/^backend = .*/backend = "keyboard"/' -e 's/^box_name = .*/box_name = "hall \\"B\\" \\\\ east"/' \
  "$example" >"$config"
grep -q '^box_name = "hall' "$config" || fail "no box_name in $example"
printf 'pcm.!default { type null }\n' >"$work/asound.conf"
start_xvfb 1280 720 || fail "Xvfb did not start"
export SDL_VIDEODRIVER=x11 ALSA_CONFIG_PATH="$work/asound.conf"
unset WAYLAND_DISPLAY
metrics="$work/state/sketch_a_scratch.prom"
(cd "$work" && HOME="$work" exec "$app" --kiosk --config "$config" --state-dir "$work/state") \
  >"$work/app.log" 2>&1 &
app_pid=$!
watch=$app_pid  # a wait ends at once when the kiosk is gone
log_has() { grep -q -- "$1" "$work/app.log" 2>/dev/null; }
until_true "log: kiosk ready" log_has '^kiosk ready' || fail "the kiosk ended or never got ready"
until_true "the metrics file" test -s "$metrics" || fail "no $metrics"
cp "$metrics" "$work/written.prom"
echo "--- $(wc -l <"$work/written.prom") lines, e.g.:"
grep -E '^sketch_a_scratch_(info|device_state\{device="pen"|strokes_total|config_accepted)' "$work/written.prom"
if ! lint=$(promtool check metrics <"$work/written.prom" 2>&1); then
  echo "$lint"
  fail "promtool check metrics rejects the kiosk's file"
fi
echo "promtool check metrics: accepted${lint:+ ($lint)}"
grep -qF 'sketch_a_scratch_info{version="' "$work/written.prom" || fail "no sketch_a_scratch_info"
grep -qF 'box="hall \"B\" \\ east"' "$work/written.prom" || fail "the box name is not in the info labels, escaped"
for texture in bubble_wrap broken_glass wooden_board cracked_ground; do
  grep -qF "sketch_a_scratch_strokes_total{texture=\"$texture\"} " "$work/written.prom" ||
    fail "no strokes counter for $texture"
done
grep -qx 'sketch_a_scratch_config_accepted 1' "$work/written.prom" || fail "the configuration is not reported accepted"
# Stopped (no write under way), only the file and the kiosk's own state files are left: no
# temporary of a write beside it.
stop_pid "$app_pid"
app_pid=""
if ls -A "$work/state" | grep -q '^\.sketch_a_scratch\.prom\.'; then
  fail "a temporary beside the metrics file: $(ls -A "$work/state" | tr '\n' ' ')"
fi
echo "PASS: the kiosk's metrics file passes promtool check metrics"

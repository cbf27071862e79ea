#!/usr/bin/env bash
# Checks the generated kiosk unit with systemd's own offline analysis (no systemd as PID 1 needed):
# the hardening exposure must stay at or below 1.5 (--threshold takes the score times ten).
set -euo pipefail
unit="$1"
command -v systemd-analyze >/dev/null || { echo "systemd-analyze missing (Debian package systemd)"; exit 1; }
report="$(systemd-analyze security --offline=true --threshold=15 "$unit" 2>&1)" || {
  echo "$report" | tail -n 40; echo "FAIL: exposure above 1.5"; exit 1; }
echo "$report" | tail -n 1

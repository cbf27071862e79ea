#!/usr/bin/env bash
# `systemd-analyze verify` on the kiosk unit as it is installed, without systemd as PID 1 and
# without touching the host: the build is installed into a staging root (DESTDIR), systemd's own
# units are copied next to it so the unit's dependencies resolve, and verify runs with --root, so
# ExecStart must name the binary that really got installed. Clean means exit status 0 AND no
# output: systemd only warns (exit 0) about unknown keys or bad values.
#   check_systemd_verify.sh <build dir>
set -euo pipefail
build="$(realpath "$1")"
command -v systemd-analyze >/dev/null || { echo "systemd-analyze missing (Debian package systemd)"; exit 1; }
stage="$(mktemp -d /tmp/sas-unit-stage.XXXXXX)"
trap 'rm -rf "$stage"' EXIT
DESTDIR="$stage" cmake --install "$build" >/dev/null
unit="$(find "$stage" -name sketch-a-scratch.service -path '*/systemd/system/*' | head -n 1)"
[ -n "$unit" ] || { echo "FAIL: cmake --install put no sketch-a-scratch.service in the stage"; exit 1; }
units="$stage/usr/lib/systemd/system"
mkdir -p "$units"
cp -rn /usr/lib/systemd/system/. "$units/"
[ "$(dirname "$unit")" = "$units" ] || cp "$unit" "$units/"
echo "installed unit: ${unit#"$stage"}"
grep '^ExecStart=' "$unit"
rc=0
# The unit's man: documentation link is checked against the staged man page, not the host's.
output="$(MANPATH="$stage/usr/share/man" systemd-analyze verify --root="$stage" sketch-a-scratch.service 2>&1)" || rc=$?
if [ "$rc" -ne 0 ] || [ -n "$output" ]; then
  echo "$output"
  echo "FAIL: systemd-analyze verify is not clean (exit $rc)"
  exit 1
fi
echo "systemd-analyze verify: clean"

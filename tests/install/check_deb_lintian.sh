#!/usr/bin/env bash
# Builds the Debian package from a configured and built tree (cpack -G DEB, into a scratch
# directory so build/ keeps its own package) and fails if lintian reports any error. Warnings and
# informational tags are printed but do not fail.
#   check_deb_lintian.sh <build dir>
set -euo pipefail
build="$(realpath "$1")"
command -v lintian >/dev/null || { echo "lintian missing (Debian package lintian)"; exit 1; }
out="$(mktemp -d /tmp/sas-deb.XXXXXX)"
trap 'rm -rf "$out"' EXIT
(cd "$build" && cpack -G DEB -B "$out" >/dev/null)
deb="$(find "$out" -maxdepth 1 -name 'sketch-a-scratch_*.deb' | head -n 1)"
[ -n "$deb" ] || { echo "FAIL: cpack made no sketch-a-scratch .deb"; exit 1; }
echo "built $(basename "$deb") ($(du -k "$deb" | cut -f1) KiB)"
# lintian refuses nothing as root but says so; drop that one line.
rc=0
report="$(lintian --fail-on error "$deb" 2>&1)" || rc=$?
echo "$report" | grep -v '^running with root privileges' || true
if [ "$rc" -ne 0 ]; then echo "FAIL: lintian reports errors"; exit 1; fi
echo "lintian: no errors"

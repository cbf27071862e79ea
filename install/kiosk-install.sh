#!/usr/bin/env bash
# Turns a fresh Debian 12 into the Sketch-a-Scratch appliance, or takes it off again.
#   sudo install/kiosk-install.sh              build, install under /usr, create the kiosk user,
#                                              config, udev rules, enable the unit (idempotent)
#   sudo install/kiosk-install.sh --uninstall  remove all of it
# The .deb (cpack -G DEB in build/) does the same through the same kiosk-provision.sh.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prefix=/usr
manifest=/var/lib/sketch-a-scratch/install_manifest.txt
die() { echo "kiosk-install.sh: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || die "run as root (sudo)"

case "${1:-install}" in
  install|--install)
    bash "$repo/install/setup.sh" build
    cmake --install "$repo/build" --prefix "$prefix"
    SAS_SHARE_DIR="$prefix/share/sketch-a-scratch" \
      sh "$prefix/share/sketch-a-scratch/kiosk-provision.sh" configure
    cp "$repo/build/install_manifest.txt" "$manifest"
    echo "kiosk-install.sh: installed; the kiosk starts at next boot (or: systemctl start sketch-a-scratch)"
    ;;
  --uninstall|uninstall)
    files=()
    [ -f "$manifest" ] && mapfile -t files < "$manifest"
    if [ -x "$prefix/share/sketch-a-scratch/kiosk-provision.sh" ]; then
      sh "$prefix/share/sketch-a-scratch/kiosk-provision.sh" remove
    else
      SAS_SHARE_DIR="$repo/install" sh "$repo/install/kiosk-provision.sh" remove
    fi
    for file in "${files[@]}"; do rm -f "$file"; done
    rm -rf "$prefix/share/sketch-a-scratch" "$prefix/share/doc/sketch-a-scratch"
    echo "kiosk-install.sh: removed ${#files[@]} installed files, the kiosk user, configuration and unit"
    ;;
  *) die "usage: kiosk-install.sh [--uninstall]" ;;
esac

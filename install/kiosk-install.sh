#!/usr/bin/env bash
# Turns a fresh Debian 12 into the Sketch-a-Scratch appliance, or takes it off again.
#   sudo install/kiosk-install.sh                   install the build packages, build in build/
#                                                   (prefix /usr), install, create the kiosk
#                                                   user, config, udev rules, enable the unit
#   sudo install/kiosk-install.sh --build-dir DIR   install an existing build (configured with
#                                                   CMAKE_INSTALL_PREFIX=/usr) without building
#   sudo install/kiosk-install.sh --uninstall       remove everything the install made
# Idempotent: running it again changes nothing that is already in place, and the configuration
# staff edited is never overwritten. The .deb (cpack -G DEB) does the same through the same
# kiosk-provision.sh.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
prefix=/usr
state_dir=/var/lib/sketch-a-scratch
manifest="$state_dir/install_manifest.txt"
created_dirs="$state_dir/created-dirs"  # directories the install made, removed again if empty
die() { echo "kiosk-install.sh: $*" >&2; exit 1; }

[ "$(id -u)" -eq 0 ] || die "run as root (sudo)"

action=install
build_dir=""
while [ $# -gt 0 ]; do
  case "$1" in
    install|--install) action=install ;;
    uninstall|--uninstall) action=uninstall ;;
    --build-dir) [ $# -ge 2 ] || die "--build-dir needs a directory"; build_dir="$2"; shift ;;
    *) die "usage: kiosk-install.sh [--build-dir DIR] [--uninstall]" ;;
  esac
  shift
done

# The prefix is compiled into the binary (data path) and the unit (ExecStart), so the build must
# have been configured with /usr; `cmake --install --prefix` could not change those afterwards.
configured_prefix() { sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$1/CMakeCache.txt" 2>/dev/null; }

install_kiosk() {
  if [ -z "$build_dir" ]; then
    bash "$repo/install/setup.sh" build
    build_dir="$repo/build"
    if [ "$(configured_prefix "$build_dir")" != "$prefix" ]; then
      cmake -S "$repo" -B "$build_dir" -DCMAKE_INSTALL_PREFIX="$prefix" >/dev/null
      cmake --build "$build_dir" -j "$(nproc 2>/dev/null || echo 2)"
    fi
  fi
  build_dir="$(cd "$build_dir" && pwd)"
  command -v cmake >/dev/null || die "cmake is needed to install a build (apt-get install cmake)"
  [ -x "$build_dir/app/sketch-a-scratch" ] || die "$build_dir holds no built app/sketch-a-scratch"
  [ "$(configured_prefix "$build_dir")" = "$prefix" ] ||
    die "$build_dir is configured for prefix '$(configured_prefix "$build_dir")', not $prefix"

  # Which directories will the install create? Install into a scratch root first and keep the
  # ones the system lacks, so --uninstall can take exactly those away again.
  mkdir -p "$state_dir"
  local stage
  stage="$(mktemp -d)"
  DESTDIR="$stage" cmake --install "$build_dir" >/dev/null
  (cd "$stage" && find . -mindepth 1 -type d | sed 's|^\.||') | while read -r dir; do
    [ -d "$dir" ] || echo "$dir"
  done >> "$created_dirs"
  rm -rf "$stage"
  sort -u -o "$created_dirs" "$created_dirs"

  cmake --install "$build_dir" >/dev/null
  touch "$manifest"
  sort -u -o "$manifest" "$manifest" "$build_dir/install_manifest.txt"
  SAS_SHARE_DIR="$prefix/share/sketch-a-scratch" \
    sh "$prefix/share/sketch-a-scratch/kiosk-provision.sh" configure
  echo "kiosk-install.sh: installed $(wc -l < "$manifest") files; the kiosk starts at next boot (or: systemctl start sketch-a-scratch)"
}

uninstall_kiosk() {
  local files=() dirs=()
  [ -f "$manifest" ] && mapfile -t files < "$manifest"
  [ -f "$created_dirs" ] && mapfile -t dirs < <(sort -r "$created_dirs")  # deepest first
  if [ -f "$prefix/share/sketch-a-scratch/kiosk-provision.sh" ]; then
    sh "$prefix/share/sketch-a-scratch/kiosk-provision.sh" stop
  else
    sh "$repo/install/kiosk-provision.sh" stop
  fi
  local file dir
  for file in "${files[@]}"; do rm -f "$file"; done
  for dir in "${dirs[@]}"; do rmdir "$dir" 2>/dev/null || true; done
  # The same as the .deb's purge: unit disabled, configuration, counters and kiosk user gone.
  sh "$repo/install/debian/postrm" purge
  echo "kiosk-install.sh: removed ${#files[@]} installed files, the kiosk user, configuration and unit"
}

case "$action" in
  install) install_kiosk ;;
  uninstall) uninstall_kiosk ;;
esac

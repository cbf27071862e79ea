#!/usr/bin/env bash
# Builds the arm64 .deb (Raspberry Pi 4/5 under Raspberry Pi OS = Debian 12 arm64) on an amd64
# Debian 12 machine, with Debian's cross compilers and the libraries as :arm64 packages.
#
#   sudo bash install/cross-build-arm64.sh [--out DIR] [--cache DIR] [--refresh]
#
# Leaves DIR/sketch-a-scratch_<version>_arm64.deb (default DIR: build-arm64 in the source tree).
# The build runs in a throwaway amd64 chroot with arm64 as a foreign architecture, never on the
# machine itself: some :arm64 packages on the host make apt remove the native gcc, g++ and binutils
# (anything that depends on gcc-12 pulls gcc-12:arm64), and other people build here. The chroot is
# made with mmdebstrap and kept as a tarball in --cache (default
# /var/cache/sketch-a-scratch-cross, or $SAS_CROSS_CACHE), keyed by its package list and options:
# it is made again when those change (install/packages.txt, build group) or with --refresh (newer
# Debian updates). The source tree is bind-mounted read-only; only the product is built (no tests,
# no benchmarks, not the calibration tools), at most 2 jobs at a lower priority. The build's logs
# go to DIR too; SAS_CROSS_KEEP=1 keeps the unpacked chroot and its build tree.
# Needs root (chroot, mounts), mmdebstrap and the Debian archive.
set -euo pipefail

repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$repo/build-arm64"
cache="${SAS_CROSS_CACHE:-/var/cache/sketch-a-scratch-cross}"
refresh=""
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out="$2"; shift ;;
    --cache) cache="$2"; shift ;;
    --refresh) refresh=1 ;;
    *) echo "usage: cross-build-arm64.sh [--out DIR] [--cache DIR] [--refresh]" >&2; exit 2 ;;
  esac
  shift
done
die() { echo "cross-build-arm64: $*" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || die "needs root (chroot and mounts)"
out="$(mkdir -p "$out" && cd "$out" && pwd)" || die "cannot make $out"
command -v mmdebstrap >/dev/null || die "mmdebstrap missing (install/packages.txt, test group)"

started=$(date +%s)
phase() { echo "cross-build-arm64: [$(($(date +%s) - started)) s] $*"; }

# ------------------------------------------------------------------ the chroot's packages
# From the build group of install/packages.txt, so that a library added there is in the chroot too:
# the libraries' -dev packages as :arm64 (what the binary links), everything else native (tools the
# build runs on this machine: cmake, pkg-config, espeak-ng, dpkg-dev, file).
native=(make qemu-user-static)
foreign=()
while read -r group package; do
  [ "$group" = build ] || continue
  case "$package" in
    build-essential) native+=(crossbuild-essential-arm64) ;;  # the cross compilers instead
    catch2|libbenchmark-dev) ;;                               # tests and benchmarks are not built
    libcli11-dev|nlohmann-json3-dev) native+=("$package") ;;   # header-only, Architecture: all
    *-dev) foreign+=("$package:arm64") ;;
    *) native+=("$package") ;;
  esac
done < <(grep -v '^#' "$repo/install/packages.txt")
packages="${native[*]} ${foreign[*]}"
mirror=http://deb.debian.org/debian
# Recommends stay out (mmdebstrap's default, said here so it stays so): they would pull in more
# :arm64 packages, each one a chance of a clash with its native twin. Documentation, manuals and
# translations are left out, and of qemu-user-static's emulators all but aarch64's (370 MB of the
# 380): nothing in the build reads them, and a smaller tarball packs and unpacks faster.
# shellcheck disable=SC2054  # the commas are mmdebstrap's own list separators
mmdebstrap_args=(
  --variant=apt --architectures=amd64,arm64 --format=tar
  --aptopt='APT::Install-Recommends "false"'
  --dpkgopt='path-exclude=/usr/share/doc/*' --dpkgopt='path-exclude=/usr/share/man/*'
  --dpkgopt='path-exclude=/usr/share/locale/*' --dpkgopt='path-exclude=/usr/share/info/*'
  --dpkgopt='path-exclude=/usr/bin/qemu-*-static'
  --dpkgopt='path-include=/usr/bin/qemu-aarch64-static'
  --include="${packages// /,}"
  bookworm
)
sources=("deb $mirror bookworm main" "deb $mirror bookworm-updates main"
         "deb http://deb.debian.org/debian-security bookworm-security main")
key=$(echo "${mmdebstrap_args[*]} ${sources[*]} v1" | sha256sum | cut -c1-16)
tarball="$cache/chroot-$key.tar"

mkdir -p "$cache"
if [ -n "$refresh" ] || [ ! -s "$tarball" ]; then
  phase "making the chroot (${#native[@]} native + ${#foreign[@]} arm64 packages) into $tarball"
  chroot_started=$(date +%s)
  mmdebstrap "${mmdebstrap_args[@]}" "$tarball.part$$" "${sources[@]}" >"$out/mmdebstrap.log" 2>&1 ||
    { rm -f "$tarball.part$$"; tail -30 "$out/mmdebstrap.log" >&2; die "mmdebstrap failed"; }
  mv "$tarball.part$$" "$tarball"
  # Older chroots (other package lists) are of no more use.
  find "$cache" -maxdepth 1 -name 'chroot-*.tar' ! -name "chroot-$key.tar" -delete
  phase "chroot made in $(($(date +%s) - chroot_started)) s ($(du -h "$tarball" | cut -f1))"
else
  phase "chroot cached: $tarball"
fi

# ------------------------------------------------------------------ the build
work="$(mktemp -d /var/tmp/sas-cross-arm64.XXXXXX)"
root="$work/root"
mounted=()
cleanup() {
  local i
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount "${mounted[i]}" 2>/dev/null || true; done
  # Never delete through a mount that is still there (the source tree is one).
  if grep -qE " ${work}[/ ]" /proc/mounts; then
    echo "cross-build-arm64: still mounted under $work, left in place" >&2
  elif [ -n "${SAS_CROSS_KEEP:-}" ]; then
    echo "cross-build-arm64: kept $work"
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP  # through the EXIT trap: unmount before anything is deleted
# In memory (about 1.5 GB with the build tree): unpacking and deleting 22,000 files on the shared
# disk took up to a minute under load, in a tmpfs a few seconds. A kept chroot stays on disk.
if [ -z "${SAS_CROSS_KEEP:-}" ]; then
  mount -t tmpfs -o size=6g,mode=0755 sas-cross "$work" || die "cannot mount a tmpfs on $work"
  mounted+=("$work")
fi
mkdir -p "$root"
tar -C "$root" -xf "$tarball" || die "cannot unpack $tarball"
phase "chroot unpacked in $work"
mkdir -p "$root/src" "$root/build"
mount --bind -o ro "$repo" "$root/src" || die "cannot bind-mount $repo"
mounted+=("$root/src")
mount -t proc proc "$root/proc" || die "cannot mount proc"
mounted+=("$root/proc")
in_root() {
  chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 "$@"
}

# The same flags as install/setup.sh's builds (line tables only; the package's binary is stripped).
phase "configuring and building (product only, -j2)"
build_started=$(date +%s)
in_root cmake -S /src -B /build \
  -DCMAKE_TOOLCHAIN_FILE=/src/cmake/toolchain-aarch64-linux-gnu.cmake \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
  -DSAS_BUILD_TESTS=OFF -DSAS_BUILD_BENCH=OFF -DCMAKE_SKIP_INSTALL_ALL_DEPENDENCY=ON \
  >"$out/configure.log" 2>&1 || { tail -30 "$out/configure.log" >&2; die "configure failed"; }
# Every library must be the arm64 one: an amd64 library folder in the cache means a search escaped
# multiarch (the binary would fail to link, or pkg-config flags came from the wrong .pc file).
if grep -E '^[^#/].*=.*/lib/x86_64-linux-gnu' "$root/build/CMakeCache.txt" >&2; then
  die "configure found amd64 files (above)"
fi
# What the package installs: the binary and the spoken cues. The calibration tools are not shipped,
# and CMAKE_SKIP_INSTALL_ALL_DEPENDENCY keeps cpack from building them.
in_root nice -n 10 cmake --build /build -j 2 --target sketch-a-scratch cues \
  >"$out/build.log" 2>&1 || { tail -40 "$out/build.log" >&2; die "build failed (see above)"; }
build_s=$(($(date +%s) - build_started))
phase "configured and built in $build_s s; packaging"
in_root sh -c 'cd /build && cpack -G DEB' >"$out/cpack.log" 2>&1 ||
  { tail -30 "$out/cpack.log" >&2; die "cpack failed"; }
debs=("$root"/build/sketch-a-scratch_*_arm64.deb)
[ -f "${debs[0]}" ] || die "cpack made no arm64 .deb: $(ls "$root/build"/*.deb 2>/dev/null)"
rm -f "$out"/sketch-a-scratch_*_arm64.deb
cp "${debs[0]}" "$out/"
deb="$out/$(basename "${debs[0]}")"
phase "configure + build + package: $(($(date +%s) - build_started)) s"
echo "cross-build-arm64: $deb"
dpkg-deb -f "$deb" Package Version Architecture Depends

#!/usr/bin/env bash
# Builds gpio-sim.ko, the kernel's GPIO simulator, for one of Debian 12's kernels, so that the
# boot test drives the token switches through a real GPIO chip. Debian's kernel does not build
# gpio-sim (nor the irq simulator it needs), so it is built out of tree from Debian's own
# linux-source-6.1 package: the kernel's code is extracted from the installed package each time
# and never kept in this repository.
#
#   sudo bash tests/appliance/gpio-sim/build-module.sh KERNEL_VERSION OUT_DIR [--arch amd64|arm64]
#
# KERNEL_VERSION is the guest's `uname -r` (e.g. 6.1.0-50-amd64); it must still be in the archive
# (its linux-headers package). Installs linux-source-6.1 and the kernel's headers, builds
# OUT_DIR/gpio-sim.ko, checks its vermagic with modinfo and prints its path. Does nothing but
# print the path when OUT_DIR/gpio-sim.ko is already built for KERNEL_VERSION. Exits 1 on failure.
#
# --arch arm64 cross-builds on this amd64 host (gcc-aarch64-linux-gnu). The arm64 headers package
# is not installed: it depends on gcc-12, which apt can only satisfy with gcc-12:arm64, and that
# removes the host's own compilers (gcc, g++, clang, binutils...). Its files are extracted into a
# scratch folder instead and built with the host's linux-kbuild-6.1 (the same tools for every
# architecture); the architecture-independent headers it needs are installed as usual.
set -uo pipefail

die() { echo "build-module: $*" >&2; exit 1; }
usage() { echo "usage: build-module.sh KERNEL_VERSION OUT_DIR [--arch amd64|arm64]" >&2; exit 2; }

arch=amd64
declare -a args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --arch) [ $# -ge 2 ] || usage; arch=$2; shift ;;
    --arch=*) arch=${1#--arch=} ;;
    -*) usage ;;
    *) args+=("$1") ;;
  esac
  shift
done
[ ${#args[@]} -eq 2 ] || usage
kver=${args[0]}
out=${args[1]}
[ "$arch" = amd64 ] || [ "$arch" = arm64 ] || die "--arch must be amd64 or arm64, not '$arch'"
# Debian's flavours end the version with the architecture; a mismatch would fetch headers for
# one architecture and build for another.
[[ "$kver" =~ ^6\.1\.[0-9]+-[0-9]+-(cloud-|rt-)?$arch$ ]] ||
  die "'$kver' is not a Debian 12 $arch kernel version (like 6.1.0-50-$arch)"
[ "$(id -u)" -eq 0 ] || die "needs root (apt-get install)"
command -v modinfo >/dev/null || die "modinfo missing (package kmod)"

ko="$out/gpio-sim.ko"
# modinfo reads the module's own .modinfo section, so it answers for a foreign architecture too.
# The trailing space keeps 6.1.0-5 from matching a module built for 6.1.0-50.
built_for() { [ -f "$1" ] && [[ "$(modinfo -F vermagic "$1" 2>/dev/null)" == "$kver "* ]]; }
if built_for "$ko"; then
  echo "$ko"
  exit 0
fi

work=$(mktemp -d /var/tmp/gpio-sim-build.XXXXXX) || die "mktemp failed"
trap 'rm -rf "$work"' EXIT
log="$work/apt.log"

# ------------------------------------------------------------------ packages
updated=""
apt_update_once() {
  [ -n "$updated" ] && return 0
  echo "build-module: apt-get update" >&2
  apt-get update -q >>"$log" 2>&1 || { tail -20 "$log" >&2; die "apt-get update failed"; }
  updated=1
}
known() { apt-cache show "$1" 2>/dev/null | grep -q '^Version:'; }  # not just a virtual name
installed() { [ "$(dpkg-query -W -f='${db:Status-Status}' "$1" 2>/dev/null)" = installed ]; }
# install PACKAGE[=VERSION]...: those not installed yet (at that version); the package lists are
# refreshed once, and only when a package is unknown to them (a new kernel ABI reaches the
# archive before the host's lists know it).
install() {
  local -a missing=()
  local p name
  for p in "$@"; do
    name=${p%%=*}
    if [ "$name" = "$p" ]; then
      installed "$name" && continue
    else
      installed "$name" && [ "$(dpkg-query -W -f='${Version}' "$name")" = "${p#*=}" ] && continue
    fi
    missing+=("$p")
    known "$p" || apt_update_once
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "build-module: apt-get install ${missing[*]}" >&2
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}" \
    >>"$log" 2>&1 || {
    tail -20 "$log" >&2
    die "apt-get install ${missing[*]} failed (is $kver still in the archive? apt-cache search linux-headers-6.1)"
  }
}

headers_pkg="linux-headers-$kver"
if [ "$arch" = amd64 ]; then
  install linux-source-6.1 "$headers_pkg"
  headers="/usr/src/linux-headers-$kver"
  headers_version=$(dpkg-query -W -f='${Version}' "$headers_pkg")
else
  install linux-source-6.1 linux-kbuild-6.1 gcc-aarch64-linux-gnu
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    # Only so that apt knows arm64's package lists; no arm64 package is installed.
    echo "build-module: dpkg --add-architecture arm64" >&2
    dpkg --add-architecture arm64 || die "dpkg --add-architecture arm64 failed"
    updated=""
  fi
  known "$headers_pkg:arm64" || apt_update_once
  (cd "$work" && apt-get download -q "$headers_pkg:arm64") >>"$log" 2>&1 ||
    { tail -20 "$log" >&2; die "apt-get download $headers_pkg:arm64 failed (is $kver still in the archive?)"; }
  deb=$(ls "$work"/linux-headers-*_arm64.deb)
  headers_version=$(dpkg-deb -f "$deb" Version)
  depends=$(dpkg-deb -f "$deb" Depends)
  # What the package would have brought: its common headers at its own version (arch all, so
  # installed like the amd64 ones) and a recent enough linux-kbuild-6.1 (amd64, the host's).
  common=$(grep -oE 'linux-headers-[^ ,]+-common[^ ,]* \(= [^)]+\)' <<<"$depends" | head -1)
  [ -n "$common" ] || die "cannot find the common headers in $headers_pkg's Depends: $depends"
  common_pkg=${common%% *}
  install "$common_pkg=$headers_version"
  kbuild_min=$(sed -nE 's/.*linux-kbuild-6\.1 \(>= ([^)]+)\).*/\1/p' <<<"$depends")
  kbuild_has=$(dpkg-query -W -f='${Version}' linux-kbuild-6.1)
  if [ -n "$kbuild_min" ] && ! dpkg --compare-versions "$kbuild_has" ge "$kbuild_min"; then
    install "linux-kbuild-6.1=$(apt-cache policy linux-kbuild-6.1 | sed -n 's/^ *Candidate: //p')"
    dpkg --compare-versions "$(dpkg-query -W -f='${Version}' linux-kbuild-6.1)" ge "$kbuild_min" ||
      die "$headers_pkg needs linux-kbuild-6.1 >= $kbuild_min; the archive's is older"
  fi
  dpkg -x "$deb" "$work/hdr" || die "cannot extract $deb"
  # The package's scripts and tools are relative links into /usr/lib/linux-kbuild-6.1: point
  # the scratch copy's /usr/lib at the host's.
  mkdir -p "$work/hdr/usr/lib"
  ln -s /usr/lib/linux-kbuild-6.1 "$work/hdr/usr/lib/linux-kbuild-6.1"
  headers="$work/hdr/usr/src/linux-headers-$kver"
fi

tarball=/usr/src/linux-source-6.1.tar.xz
[ -f "$headers/Makefile" ] || die "no kernel headers at $headers"
[ -f "$tarball" ] || die "no $tarball (package linux-source-6.1)"
# The three files come from the source package's version rather than the kernel's; they rarely
# change within 6.1 (6.1.176 and 6.1.192 have the same three files). Said, not refused.
source_version=$(dpkg-query -W -f='${Version}' linux-source-6.1)
[ "${source_version%-*}" = "${headers_version%-*}" ] ||
  echo "build-module: note: the driver's source is linux ${source_version%-*}, the kernel's ${headers_version%-*}" >&2

# ------------------------------------------------------------------ build
tar -xJf "$tarball" -C "$work" --strip-components=1 --wildcards \
  '*/drivers/gpio/gpio-sim.c' '*/drivers/gpio/gpiolib.h' '*/kernel/irq/irq_sim.c' ||
  die "cannot extract gpio-sim.c, gpiolib.h and irq_sim.c from $tarball"
mod="$work/mod"
mkdir "$mod"
# Named apart from the module: gpio-sim.o is the linked module, made of the driver and the irq
# simulator that this kernel lacks (without it modpost finds devm_irq_domain_create_sim undefined).
mv "$work/drivers/gpio/gpio-sim.c" "$mod/gpio-sim-main.c"
mv "$work/drivers/gpio/gpiolib.h" "$mod/gpiolib.h"
mv "$work/kernel/irq/irq_sim.c" "$mod/irq_sim.c"
# irq_to_desc is not exported to modules in 6.1; generic_handle_irq does the same from the irq
# number (looks the descriptor up and runs its flow handler, handle_simple_irq here).
pattern='handle_simple_irq(irq_to_desc(irqnum))'
grep -qF "$pattern" "$mod/irq_sim.c" ||
  die "irq_sim.c ($source_version) has no '$pattern' any more: the out-of-tree fix needs another look"
sed -i 's/handle_simple_irq(irq_to_desc(irqnum))/generic_handle_irq(irqnum)/' "$mod/irq_sim.c"
grep -qF "$pattern" "$mod/irq_sim.c" && die "could not replace '$pattern' in irq_sim.c"
cat >"$mod/Kbuild" <<'EOF'
obj-m := gpio-sim.o
gpio-sim-y := gpio-sim-main.o irq_sim.o
ccflags-y := -I$(src)
EOF
declare -a make_args=(-C "$headers" M="$mod" modules)
[ "$arch" = arm64 ] && make_args+=(ARCH=arm64 CROSS_COMPILE=aarch64-linux-gnu-)
if ! make "${make_args[@]}" >"$work/make.log" 2>&1; then
  tail -30 "$work/make.log" >&2
  die "the module build failed (make ${make_args[*]})"
fi
built_for "$mod/gpio-sim.ko" ||
  die "the built module's vermagic is '$(modinfo -F vermagic "$mod/gpio-sim.ko" 2>&1)', not $kver"
mkdir -p "$out" || die "cannot make $out"
# Copied under another name, then renamed: a reader never sees half a module.
{ cp "$mod/gpio-sim.ko" "$out/.gpio-sim.ko.part" && mv "$out/.gpio-sim.ko.part" "$ko"; } ||
  die "cannot write $ko"
echo "$ko"

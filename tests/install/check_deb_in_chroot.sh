#!/usr/bin/env bash
# Installs the kiosk's .deb into a fresh Debian 12 root (debootstrap, minbase), checks that the
# unit, udev rules, user and configuration land in place, removes it with `apt-get remove` (the
# configuration and counters stay), purges it, and checks that nothing the package made is left. Needs root, debootstrap and the Debian archive.
# With a build directory as third argument it then checks install/kiosk-install.sh in the same
# root: install, install again (idempotent: nothing changes, the staff's configuration edit
# survives), --uninstall (nothing left). The repository is bind-mounted at its own path.
#   check_deb_in_chroot.sh <package.deb> [<pristine debootstrap root to copy> [<build dir>]]
set -euo pipefail
deb="$(realpath "$1")"
pristine="${2:-}"
build_dir="${3:+$(realpath "$3")}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
work="$(mktemp -d /tmp/sas-deb-root.XXXXXX)"
root="$work/root"
cleanup() {
  umount "$root$repo" 2>/dev/null || true
  umount "$root/proc" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

if [ -n "$pristine" ]; then
  cp -a "$pristine" "$root"
else
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >/dev/null
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount -t proc proc "$root/proc"
in_root() { chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive "$@"; }

cp "$deb" "$root/tmp/kiosk.deb"
in_root apt-get update -q >/dev/null
# Install the dependencies first so the before/after comparison sees only what the package made.
deps="$(dpkg-deb -f "$deb" Depends | sed -E 's/\([^)]*\)//g; s/,/ /g')"
in_root apt-get install -y -q --no-install-recommends $deps >/dev/null
snapshot() {
  (cd "$root" && find . -xdev \( -path ./proc -o -path ./tmp -o -path ./var/cache -o -path ./var/lib/apt \
    -o -path ./var/lib/dpkg -o -path ./var/log -o -path ./run -o -path "./${repo#/}" \) -prune -o -print | sort |
    grep -vE '^\./etc/(passwd|group|shadow|gshadow)-$')  # shadow-utils' own backups of the admin's files
  grep -E '^(sas-kiosk|gpio|render|plugdev|input|video|audio):' "$root/etc/passwd" "$root/etc/group" || true
}
snapshot > "$work/before.txt"

in_root apt-get install -y -q "/tmp/kiosk.deb" >/dev/null
fail=0
for path in usr/bin/sketch-a-scratch usr/lib/systemd/system/sketch-a-scratch.service \
            usr/lib/udev/rules.d/60-sketch-a-scratch.rules etc/sketch-a-scratch/kiosk.toml \
            usr/lib/modprobe.d/sketch-a-scratch.conf usr/share/man/man1/sketch-a-scratch.1.gz \
            usr/share/sketch-a-scratch/materials/wood.toml \
            usr/share/sketch-a-scratch/textures/wooden_board/picture.png \
            usr/share/sketch-a-scratch/cues/wooden_board_name.wav \
            etc/systemd/system/multi-user.target.wants/sketch-a-scratch.service; do
  if [ -e "$root/$path" ] || [ -L "$root/$path" ]; then echo "installed: /$path"; else echo "MISSING: /$path"; fail=1; fi
done
if in_root getent passwd sas-kiosk >/dev/null; then
  echo "installed: user sas-kiosk in groups: $(in_root id -nG sas-kiosk)"
else
  echo "MISSING: user sas-kiosk"; fail=1
fi
in_root sketch-a-scratch --version
unit=/usr/lib/systemd/system/sketch-a-scratch.service
# --man=no: a minbase root has no man command to look up the unit's man: link; the page itself is in
# the path list above, and the build's own verify test checks the link against the staged page.
if verify="$(in_root systemd-analyze verify --man=no "$unit" 2>&1)" && [ -z "$verify" ]; then
  echo "systemd-analyze verify: clean"
else
  echo "FAIL: systemd-analyze verify: $verify"; fail=1
fi
if exposure="$(in_root systemd-analyze security --offline=true --threshold=15 "$unit" 2>&1 | tail -n 1)"; then
  echo "installed unit: $exposure"
else
  echo "FAIL: installed unit: $exposure"; fail=1
fi

echo "counted = 1" > "$root/var/lib/sketch-a-scratch/counters.toml"  # stands for the usage counters
in_root apt-get remove -y -q sketch-a-scratch >/dev/null
for path in etc/sketch-a-scratch/kiosk.toml var/lib/sketch-a-scratch/counters.toml; do
  if [ -e "$root/$path" ]; then echo "apt-get remove kept /$path"; else echo "FAIL: apt-get remove deleted /$path"; fail=1; fi
done
[ -e "$root/usr/bin/sketch-a-scratch" ] && { echo "FAIL: apt-get remove left the binary"; fail=1; }
in_root apt-get purge -y -q sketch-a-scratch >/dev/null
snapshot > "$work/after.txt"
if ! diff "$work/before.txt" "$work/after.txt"; then
  echo "FAIL: apt-get purge left the differences above"; fail=1
else
  echo "apt-get purge left nothing behind"
fi

if [ -n "$build_dir" ]; then
  echo "--- install/kiosk-install.sh --build-dir $build_dir"
  in_root apt-get install -y -q --no-install-recommends cmake >/dev/null
  snapshot > "$work/before-script.txt"
  mkdir -p "$root$repo"
  mount --bind "$repo" "$root$repo"
  in_root bash "$repo/install/kiosk-install.sh" --build-dir "$build_dir"
  for path in usr/bin/sketch-a-scratch usr/lib/systemd/system/sketch-a-scratch.service \
              usr/lib/udev/rules.d/60-sketch-a-scratch.rules etc/sketch-a-scratch/kiosk.toml \
              usr/share/sketch-a-scratch/textures/wooden_board/texture.toml \
              etc/systemd/system/multi-user.target.wants/sketch-a-scratch.service; do
    [ -e "$root/$path" ] || [ -L "$root/$path" ] || { echo "MISSING after kiosk-install.sh: /$path"; fail=1; }
  done
  in_root getent passwd sas-kiosk >/dev/null || { echo "MISSING after kiosk-install.sh: user sas-kiosk"; fail=1; }
  echo "# staff edit" >> "$root/etc/sketch-a-scratch/kiosk.toml"
  snapshot > "$work/after-first.txt"
  in_root bash "$repo/install/kiosk-install.sh" --build-dir "$build_dir"
  snapshot > "$work/after-second.txt"
  if diff "$work/after-first.txt" "$work/after-second.txt"; then
    echo "kiosk-install.sh run twice: second run changed nothing"
  else
    echo "FAIL: the second kiosk-install.sh run changed the files above"; fail=1
  fi
  if tail -n 1 "$root/etc/sketch-a-scratch/kiosk.toml" | grep -qx "# staff edit"; then
    echo "kiosk-install.sh kept the staff's configuration edit"
  else
    echo "FAIL: kiosk-install.sh overwrote /etc/sketch-a-scratch/kiosk.toml"; fail=1
  fi
  in_root bash "$repo/install/kiosk-install.sh" --uninstall
  umount "$root$repo"
  rmdir "$root$repo" 2>/dev/null || true
  (cd "$root" && p="${repo#/}"; while [ "$p" != . ] && [ -n "$p" ]; do rmdir "$p" 2>/dev/null || true; p="$(dirname "$p")"; done)
  snapshot > "$work/after-uninstall.txt"
  if diff "$work/before-script.txt" "$work/after-uninstall.txt"; then
    echo "kiosk-install.sh --uninstall left nothing behind"
  else
    echo "FAIL: kiosk-install.sh --uninstall left the differences above"; fail=1
  fi
fi
exit "$fail"

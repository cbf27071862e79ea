#!/bin/sh
# Sets up (configure) or tears down (remove) everything around the installed files that turns a
# Debian 12 machine into the kiosk: the kiosk user and its groups, the staff-editable
# configuration, udev and systemd. Shared by install/kiosk-install.sh and the .deb's maintainer
# scripts so both do exactly the same. Idempotent; POSIX sh (dpkg runs it without bash).
set -eu

user=sas-kiosk
state_dir=/var/lib/sketch-a-scratch
config_dir=/etc/sketch-a-scratch
unit=sketch-a-scratch.service
share_dir="${SAS_SHARE_DIR:-/usr/share/sketch-a-scratch}"
groups="video render input audio gpio plugdev"

have() { command -v "$1" >/dev/null 2>&1; }

configure() {
  mkdir -p "$state_dir"
  for group in $groups; do
    if ! getent group "$group" >/dev/null; then
      groupadd --system "$group"
      echo "$group" >> "$state_dir/created-groups"
    fi
  done
  if ! getent passwd "$user" >/dev/null; then
    useradd --system --home-dir "$state_dir" --no-create-home --shell /usr/sbin/nologin \
      --user-group --comment "Sketch-a-Scratch kiosk" "$user"
  fi
  usermod --append --groups "$(echo $groups | tr ' ' ',')" "$user"
  chown "$user:$user" "$state_dir"
  if [ ! -e "$config_dir/kiosk.toml" ]; then
    mkdir -p "$config_dir"
    cp "$share_dir/kiosk.toml" "$config_dir/kiosk.toml"
    chmod 0644 "$config_dir/kiosk.toml"
  fi
  if have udevadm && [ -d /run/udev ]; then
    udevadm control --reload-rules || true
    udevadm trigger --subsystem-match=gpio --subsystem-match=hidraw --subsystem-match=input || true
  fi
  if have systemctl; then
    # Works offline too (in a chroot or image build) by creating the [Install] symlinks.
    [ -d /run/systemd/system ] && systemctl daemon-reload || true
    systemctl enable "$unit" >/dev/null 2>&1 || systemctl enable "$unit"
  fi
}

remove() {
  if have systemctl; then
    [ -d /run/systemd/system ] && systemctl stop "$unit" 2>/dev/null || true
    systemctl disable "$unit" >/dev/null 2>&1 || true
  fi
  rm -rf "$config_dir"
  if getent passwd "$user" >/dev/null; then userdel "$user" 2>/dev/null || true; fi
  if getent group "$user" >/dev/null; then groupdel "$user" 2>/dev/null || true; fi
  if [ -f "$state_dir/created-groups" ]; then
    while read -r group; do
      getent group "$group" >/dev/null && groupdel "$group" 2>/dev/null || true
    done < "$state_dir/created-groups"
  fi
  rm -rf "$state_dir" /var/log/sketch-a-scratch
}

case "${1:-}" in
  configure) configure ;;
  remove) remove ;;
  *) echo "usage: kiosk-provision.sh configure|remove" >&2; exit 2 ;;
esac

#!/bin/sh
# Sets up (configure) everything around the installed files that turns a Debian 12 machine into
# the kiosk: the kiosk user and its groups, the staff-editable configuration, udev and systemd;
# stop stops a running kiosk. Shared by install/kiosk-install.sh and the .deb's maintainer scripts
# so both do exactly the same; taking it off again is install/debian/postrm (remove, purge), which
# must work after this file is gone. Idempotent; POSIX sh (dpkg runs it without bash).
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
  # Where staff put their recorded cues (kiosk.toml [paths] staff_dir): made once, then theirs.
  [ -d "$config_dir/cues" ] || install -d -m 0755 "$config_dir/cues"
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

stop() {
  if have systemctl && [ -d /run/systemd/system ]; then
    systemctl stop "$unit" 2>/dev/null || true
  fi
}

case "${1:-}" in
  configure) configure ;;
  stop) stop ;;
  *) echo "usage: kiosk-provision.sh configure|stop" >&2; exit 2 ;;
esac

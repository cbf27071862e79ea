#!/bin/bash
# A real kernel GPIO chip for the kiosk's token switches, inside the boot test's VM (run as root).
# gpio-sim (built by tests/appliance/gpio-sim/build-module.sh) makes a chip whose lines the kiosk
# reads through /dev/gpiochipN like a board's; this script makes the chip and plays the switches
# by setting each line's simulated pull: a token placed closes an active-low switch against the
# pull-up (pull-down), a token lifted lets the pull-up win.
#
#   gpio-sim.sh setup KO_PATH LABEL NAME...   one bank, a line per NAME; prints /dev/gpiochipN
#   gpio-sim.sh pull LABEL LINE_OFFSET up|down
#   gpio-sim.sh chatter LABEL LINE_OFFSET N   N alternating pulls as fast as the shell writes,
#                                             the last one down (a token placed on chattering ink)
#   gpio-sim.sh value LABEL LINE_OFFSET       the line's value as the chip sees it (0 or 1)
#   gpio-sim.sh press LABEL LINE_OFFSET SECONDS   a button pressed (pulled down) for SECONDS, then
#                                             released; prints how long it really was held
#
# Needs only bash and the kernel's sysfs and configfs (the guest has no libgpiod tools). Exits
# non-zero with a message on failure.
set -uo pipefail

die() { echo "gpio-sim.sh: $*" >&2; exit 1; }
usage() {
  echo "usage: gpio-sim.sh setup KO_PATH LABEL NAME... | pull LABEL LINE_OFFSET up|down |" \
    "chatter LABEL LINE_OFFSET N | press LABEL LINE_OFFSET SECONDS | value LABEL LINE_OFFSET" >&2
  exit 2
}
config=/sys/kernel/config
# Generous: the boot test's guest is emulated (TCG) on two shared cores.
deadline_s=${GPIO_SIM_DEADLINE_S:-60}

# wait_for SECONDS COMMAND...: polls the command until it succeeds or the deadline passes.
wait_for() {
  local limit=$(($(date +%s) + $1))
  shift
  until "$@"; do
    [ "$(date +%s)" -lt "$limit" ] || return 1
    sleep 0.05
  done
}

# sim_chip LABEL: the sysfs folder of the gpio-sim chip with that label (its gpiochipN device,
# /sys/devices/platform/gpio-sim.M/gpiochipN, where the sim_gpioN attributes are). Found through
# configfs, which names each bank's platform device and chip: in 6.1 the chip's own sysfs folder
# has no label, and the legacy class entry that has one hangs off the platform device, shared by
# all of its banks.
sim_chip() {
  local bank dev name found=""
  for bank in "$config"/gpio-sim/*/bank*; do
    [ -d "$bank" ] && [ "$(cat "$bank/label" 2>/dev/null)" = "$1" ] || continue
    name=$(cat "$bank/chip_name" 2>/dev/null)  # "none" until the chip is live
    dev=$(cat "${bank%/*}/dev_name" 2>/dev/null)
    [ -n "$name" ] && [ "$name" != none ] && [ -d "/sys/devices/platform/$dev/$name" ] || continue
    [ -z "$found" ] || { echo "gpio-sim.sh: two gpio-sim chips are labelled '$1'" >&2; return 1; }
    found="/sys/devices/platform/$dev/$name"
  done
  [ -n "$found" ] && echo "$found"
}

chip_device_ready() {  # the chip exists and its character device is there
  local dir
  dir=$(sim_chip "$1" 2>/dev/null) || return 1
  [ -c "/dev/${dir##*/}" ]
}

# line_dir LABEL OFFSET: the folder of that line's value and pull.
line_dir() {
  local dir
  [[ "$2" =~ ^[0-9]+$ ]] || die "line offset '$2' is not a number"
  dir=$(sim_chip "$1") || die "no gpio-sim chip labelled '$1'"
  [ -d "$dir/sim_gpio$2" ] || die "chip '$1' ($(basename "$dir")) has no line $2"
  echo "$dir/sim_gpio$2"
}

setup() {
  [ $# -ge 3 ] || usage
  local ko=$1 label=$2
  shift 2
  [ -f "$ko" ] || die "no module at $ko"
  [ "$(id -u)" -eq 0 ] || die "needs root"
  # configfs first: gpio-sim depends on it, and insmod (unlike modprobe) does not load it.
  if ! grep -qw configfs /proc/filesystems; then
    modprobe configfs || die "cannot load configfs"
  fi
  if ! grep -q " $config configfs " /proc/mounts; then
    mount -t configfs none "$config" || die "cannot mount configfs on $config"
  fi
  if [ ! -d /sys/module/gpio_sim ]; then
    insmod "$ko" || die "insmod $ko failed (built for $(modinfo -F vermagic "$ko" 2>/dev/null || echo '?'), kernel $(uname -r))"
  fi
  [ -d "$config/gpio-sim" ] || die "gpio-sim loaded but $config/gpio-sim is missing"
  sim_chip "$label" >/dev/null 2>&1 && die "a gpio-sim chip labelled '$label' exists already"
  # The configfs folder is named after the label, which keeps one chip per label.
  local chip="$config/gpio-sim/${label//[^A-Za-z0-9_-]/_}" i=0 name
  [ -e "$chip" ] && die "$chip exists already"
  mkdir "$chip" && mkdir "$chip/bank0" || die "cannot make $chip/bank0"
  echo $# >"$chip/bank0/num_lines" || die "cannot set num_lines"
  echo "$label" >"$chip/bank0/label" || die "cannot set the label"
  for name in "$@"; do
    mkdir "$chip/bank0/line$i" && echo "$name" >"$chip/bank0/line$i/name" ||
      die "cannot name line $i '$name'"
    i=$((i + 1))
  done
  echo 1 >"$chip/live" || die "the kernel refused the chip (echo 1 > $chip/live; see dmesg)"
  wait_for "$deadline_s" chip_device_ready "$label" ||
    die "no /dev/gpiochipN for '$label' after ${deadline_s} s"
  # gpio-sim starts every line pulled down, which an active-low switch reads as a token placed:
  # start from the board's idle state, every token lifted.
  local dir
  dir=$(sim_chip "$label") || die "lost the chip '$label'"
  for ((i = 0; i < $#; i++)); do
    echo pull-up >"$dir/sim_gpio$i/pull" || die "cannot pull line $i up"
  done
  # Under udev, the device's group and mode (the package's rule) are set after the node exists:
  # let it finish, so the kiosk's user can open the chip as soon as this returns.
  if command -v udevadm >/dev/null; then udevadm settle -t "$deadline_s" || true; fi
  echo "/dev/${dir##*/}"
}

pull() {
  [ $# -eq 3 ] || usage
  local line
  line=$(line_dir "$1" "$2") || exit 1
  case "$3" in
    up | down) echo "pull-$3" >"$line/pull" || die "cannot write pull-$3 to $line/pull" ;;
    *) usage ;;
  esac
}

# A visitor's press is its own length of time, not a wait for an event: the kiosk judges a press
# on the kernel's edge timestamps (shorter than the debounce: a glitch; longer than the long hold:
# a cancel), so the press is held for a set time from the moment the chip reads the line low, and
# the length it really had is printed for the report. The file stays open: no fork between the
# two writes.
press() {
  [ $# -eq 3 ] || usage
  local line
  line=$(line_dir "$1" "$2") || exit 1
  exec {fd}>"$line/pull" || die "cannot open $line/pull"
  echo pull-down >&"$fd" || die "cannot write $line/pull"
  local start=$EPOCHREALTIME
  wait_for 60 value_is "$line" 0 || die "line $2 did not read low after pull-down"
  sleep "$3"
  echo pull-up >&"$fd" || die "cannot write $line/pull"
  local end=$EPOCHREALTIME
  exec {fd}>&-
  echo "press: line $2 held $(( (${end//[.,]/} - ${start//[.,]/}) / 1000 )) ms"
}

value_is() { [ "$(cat "$1/value")" = "$2" ]; }

chatter() {
  [ $# -eq 3 ] || usage
  local line n=$3 i
  [[ "$n" =~ ^[1-9][0-9]*$ ]] || die "the toggle count '$n' is not a positive number"
  line=$(line_dir "$1" "$2") || exit 1
  # The file stays open and bash writes it without forking, so the burst lasts well under a
  # debounce interval even on an emulated machine; it says how long it took. Counted back from
  # the last write, which is the pull-down: odd distances are up, even ones down.
  local start=$EPOCHREALTIME
  exec {fd}>"$line/pull" || die "cannot open $line/pull"
  for ((i = n - 1; i >= 0; i--)); do
    if ((i % 2)); then echo pull-up >&"$fd"; else echo pull-down >&"$fd"; fi || die "cannot write $line/pull"
  done
  exec {fd}>&-
  local end=$EPOCHREALTIME
  echo "chatter: $n pulls in $(( (${end//[.,]/} - ${start//[.,]/}) / 1000 )) ms, ends pull-down"
}

value() {
  [ $# -eq 2 ] || usage
  local line
  line=$(line_dir "$1" "$2") || exit 1
  cat "$line/value"
}

[ $# -ge 1 ] || usage
command=$1
shift
case "$command" in
  setup) setup "$@" ;;
  pull) pull "$@" ;;
  chatter) chatter "$@" ;;
  press) press "$@" ;;
  value) value "$@" ;;
  *) usage ;;
esac

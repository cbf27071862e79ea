#!/bin/bash
# The visitor, the member of staff and the installer, inside the appliance VM (run as root by
# sas-visitor.service of the test image once the box has booted). It plays the session with the
# fake devices (fake_devices through /run/sas-fake/ctl), asks the host for screenshots through
# the shared folder (out/req/NAME -> the host writes out/shots/NAME.ppm and out/ack/NAME), records
# the speaker and transducer from the loopback card, and writes what it measured to
# out/results.txt: "PASS|FAIL <check> <details>" for what it can judge here, "value <name> <v>"
# and "mark <name> <seconds into the capture>" for the host's checks. Ends by powering off.
set -u
share=/mnt/sas
out=$share/out
ctl=/run/sas-fake/ctl
status=/run/sas-fake/status
unit=sketch-a-scratch.service
mkdir -p "$out/req" "$out/ack" "$out/cues"
exec >>"$out/guest.log" 2>&1
trap 'journalctl -b -o short-monotonic --no-pager >"$out/journal.txt" 2>&1; sync; systemctl poweroff' EXIT

now() { cut -d' ' -f1 /proc/uptime; }
log() { echo "[$(now)] $*"; }
result() { echo "$*" >>"$out/results.txt"; log "$*"; }
pass() { result "PASS $*"; }
fail() { result "FAIL $*"; }
judge() {  # judge <check name> <details> <command...>: PASS or FAIL on the command's status
  local name=$1 details=$2
  shift 2
  if "$@"; then pass "$name $details"; else fail "$name $details"; fi
}
value() { result "value $1 $2"; }
sub() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a - b }'; }
le() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a <= b) }'; }

# Commands are numbered by the device emulator from its start (the unit plugged three devices).
commands=$(grep -c '' "$status" 2>/dev/null || echo 0)
dev() {  # one fake-device command, waiting until it is done
  commands=$((commands + 1))
  echo "$*" >"$ctl"
  for _ in $(seq 600); do
    grep -q "^ok $commands " "$status" 2>/dev/null && return 0
    grep -q "^error $commands " "$status" 2>/dev/null && { log "device command failed: $(grep "^error $commands " "$status")"; return 1; }
    sleep 0.1
  done
  log "device command timed out: $*"
  return 1
}
shot() {  # shot NAME: the host takes a screenshot now
  touch "$out/req/$1"
  for _ in $(seq 600); do [ -e "$out/ack/$1" ] && return 0; sleep 0.1; done
  log "screenshot $1 timed out"
  return 1
}
main_pid() { systemctl show -p MainPID --value "$unit"; }
active() { [ "$(systemctl show -p ActiveState --value "$unit")" = active ]; }
since=""
mark_journal() { since=$(date +%s.%N); }
# wait_journal PATTERN SECONDS [PRIORITY]: a kiosk line since the last mark_journal matches
wait_journal() {
  local priority=${3:-debug}
  for _ in $(seq $(($2 * 5))); do
    journalctl -u "$unit" -p "$priority" --since "@$since" -o cat --no-pager 2>/dev/null | grep -q -- "$1" && return 0
    sleep 0.2
  done
  return 1
}
wait_active_pid() {  # wait_active_pid OLD_PID SECONDS: a new main process that reached READY
  for _ in $(seq $(($2 * 10))); do
    local pid
    pid=$(main_pid)
    if active && [ "$pid" != 0 ] && [ "$pid" != "$1" ]; then return 0; fi
    sleep 0.1
  done
  return 1
}
ready_s() { awk '{ printf "%.2f", $1 / 1e6 }' <<<"$(systemctl show -p ActiveEnterTimestampMonotonic --value "$unit")"; }
capture_t0=""
mark() { value "mark_$1" "$(sub "$(now)" "$capture_t0")"; }

log "visitor starts"
# --- 1. the unit comes up: READY (Type=notify: active), watchdog pings, security exposure
for _ in $(seq 1200); do active && break; sleep 0.1; done
judge unit_active "state $(systemctl show -p ActiveState --value $unit)/$(systemctl show -p SubState --value $unit)" active
value ready_uptime_s "$(ready_s)"
value kernel_to_userspace "$(systemd-analyze 2>/dev/null | head -1)"
w1=$(systemctl show -p WatchdogTimestampMonotonic --value "$unit")
sleep 4
w2=$(systemctl show -p WatchdogTimestampMonotonic --value "$unit")
judge watchdog_pings "last ping at ${w1} then ${w2} us" test "${w2:-0}" -gt "${w1:-0}"
judge watchdog_armed "WatchdogUSec=$(systemctl show -p WatchdogUSec --value $unit)" \
  test "$(systemctl show -p WatchdogUSec --value $unit)" != 0
exposure=$(systemd-analyze security "$unit" 2>/dev/null | sed -n 's/.*Overall exposure level for [^:]*: \([0-9.]*\).*/\1/p')
judge security_exposure "systemd-analyze security: ${exposure:-?}" le "${exposure:-99}" 1.5
restarts0=$(systemctl show -p NRestarts --value "$unit")
value restarts_at_boot "$restarts0"
journalctl -u "$unit" -b -o cat --no-pager | grep -i 'cue' | head -5
# One folder of cues per language, each with the four textures' names; the default language's
# go to the host, which looks for them on the speaker.
judge cues_installed "$(ls /usr/share/sketch-a-scratch/cues 2>/dev/null | tr '\n' ' ')languages, $(ls /usr/share/sketch-a-scratch/cues/*/*_name.wav 2>/dev/null | wc -l) name cues" \
  test "$(ls /usr/share/sketch-a-scratch/cues/*/*_name.wav 2>/dev/null | wc -l)" -eq 20
cp /usr/share/sketch-a-scratch/cues/en/*.wav "$out/cues/" 2>/dev/null
judge no_cue_warning "journal" \
  bash -c "! journalctl -u $unit -b -p warning -o cat --no-pager | grep -q 'spoken cues'"

# --- 2./3. the stroke: screen and sound. Capture the loopback's other end for the whole visit.
arecord -q -D plughw:CARD=Loopback,DEV=1,SUBDEV=0 -f FLOAT_LE -c 2 -r 48000 -t raw "$out/capture.f32" &
capture_pid=$!
capture_t0=$(now)
sleep 1
dev down 0.05 0.05 0.3 0 && dev up  # a first touch leaves the attract screen
sleep 1.5
shot explore
mark_journal
mark stroke_down
dev down 0.35 0.50 0.5 10
dev drag 0.60 0.55 1.2 0.5 10
mark stroke_last_move
# The pen rests where the drag ended while the emulated machine's slow frames catch up with it.
sleep 2
shot dent
mark stroke_lift
dev up
sleep 3
mark stroke_quiet

# --- 4. a token on the MCP2221A: texture switch on screen, its spoken name on the speaker
mark_journal
mark token_on
dev token 2 on
judge token_switch "journal: showing broken_glass" wait_journal 'showing broken_glass' 20
sleep 3.5
shot token
mark token_cue_end
dev token 2 off
wait_journal 'showing wooden_board' 20

# --- 5. the voice: record key, the WAV at the microphone, the surface; wiped at the idle reset
mark_journal
dev key r tap
if wait_journal 'recording started' 60; then
  pass recording_started "record key R"
  aplay -q -D plughw:CARD=Loopback,DEV=1,SUBDEV=0 -t raw -f S16_LE -c 1 -r 48000 "$share/voice.s16"
  judge voice_surface "journal: showing the voice" wait_journal 'showing the voice' 60
  sleep 1.5
  shot voice
  judge voice_wiped "journal: voice wiped after the idle timeout" wait_journal 'voice wiped' 90
else
  fail recording_started "no 'recording started' line"
fi

# --- 6. signals: SIGHUP handled, SIGSEGV during a recording restarts quickly and dumps nothing,
# SIGSTOP is caught by systemd's watchdog
counters=/var/lib/sketch-a-scratch/counters.toml
cp "$counters" "$out/counters-before-hup.toml" 2>/dev/null
pid=$(main_pid)
mark_journal
kill -HUP "$pid"
sleep 2
judge sighup_keeps_running "pid $pid -> $(main_pid)" test "$(main_pid)" = "$pid"
judge sighup_journal "journal line" wait_journal 'SIGHUP' 10
cp "$counters" "$out/counters-after-hup.toml" 2>/dev/null
visits() { sed -n 's/^sessions *= *\([0-9]*\).*/\1/p' "$1" 2>/dev/null | head -1; }
judge sighup_counts_kept "visits $(visits "$out/counters-before-hup.toml") -> $(visits "$out/counters-after-hup.toml")" \
  test "$(visits "$out/counters-after-hup.toml")" -ge "$(visits "$out/counters-before-hup.toml")"

mark_journal
dev key r tap
if wait_journal 'recording started' 60; then
  aplay -q -D plughw:CARD=Loopback,DEV=1,SUBDEV=0 -t raw -f S16_LE -c 1 -r 48000 "$share/voice.s16" &
  aplay_pid=$!
  sleep 1.5
  pid=$(main_pid)
  t_kill=$(now)
  kill -SEGV "$pid"
  if wait_active_pid "$pid" 90; then
    # Split at the new process's exec: systemd's part (crash noticed, RestartSec) runs in real
    # time here; the kiosk's own start is CPU work, slowed down by the emulation (the host
    # measures it natively and judges the 5 s).
    exec_s=$(awk '{ printf "%.2f", $1 / 1e6 }' <<<"$(systemctl show -p ExecMainStartTimestampMonotonic --value "$unit")")
    exit_s=$(awk '{ printf "%.2f", $1 / 1e6 }' <<<"$(systemctl show -p ExecMainExitTimestampMonotonic --value "$unit")")
    # The old process's end (its core dump written) and the restart delay, when systemd still
    # holds the old exit time.
    if le "$exit_s" "$exec_s" && le "$t_kill" "$exit_s"; then
      value segv_crash_handling_s "$(sub "$exit_s" "$t_kill")"
      value segv_restart_delay_s "$(sub "$exec_s" "$exit_s")"
    fi
    value segv_to_exec_s "$(sub "$exec_s" "$t_kill")"
    value segv_kiosk_start_s "$(sub "$(ready_s)" "$exec_s")"
    value segv_to_ready_s "$(sub "$(ready_s)" "$t_kill")"
    pass segv_restart "exploring again $(sub "$(ready_s)" "$t_kill") s after SIGSEGV in the VM: systemd restarted it after $(sub "$exec_s" "$t_kill") s, its start took $(sub "$(ready_s)" "$exec_s") s"
  else
    fail segv_restart "no new kiosk within 90 s"
  fi
  wait "$aplay_pid"
  sleep 3
  coredumpctl list --no-pager 2>&1 | tee "$out/coredumps.txt"
  # Debian's systemd-coredump keeps a dump whatever LimitCORE says; the unit's CoredumpFilter
  # leaves only ELF headers in it (the disk search on the host looks for the voice itself).
  core=$(ls -S /var/lib/systemd/coredump/core.sketch-a-scratc* 2>/dev/null | head -1)
  core_kb=$([ -n "$core" ] && du -k "$core" | cut -f1 || echo 0)
  judge segv_core_small "kiosk core dump ${core_kb} kB on disk" test "$core_kb" -lt 16384
else
  fail segv_restart "no recording to crash"
fi
# The control: the same crash of a process that holds other voice samples in ordinary memory,
# with core dumps allowed, does leave them on the disk (so the host's disk search can see one).
systemd-run --unit=sas-core-control -p LimitCORE=infinity "$share/bin/fake_devices" hold "$share/control.f32"
sleep 2
kill -SEGV "$(systemctl show -p MainPID --value sas-core-control)"
sleep 5
judge core_control "coredumpctl lists the control's core" \
  bash -c "coredumpctl list --no-pager 2>/dev/null | grep -q fake_devices"

pid=$(main_pid)
mark_journal
t_stop=$(now)
kill -STOP "$pid"
if wait_active_pid "$pid" 90; then
  value sigstop_to_ready_s "$(sub "$(ready_s)" "$t_stop")"
  pass sigstop_watchdog "restarted $(sub "$(ready_s)" "$t_stop") s after SIGSTOP"
  judge sigstop_watchdog_journal "journal: watchdog timeout" \
    bash -c "journalctl -u $unit --since @$since -o cat --no-pager | grep -qi 'watchdog timeout'"
else
  fail sigstop_watchdog "not restarted within 90 s"
fi
sleep 3

# --- 7. devices unplugged and back: a warning line, a staff-panel line, working again
dev chord 2.5
judge staff_panel_opens "journal: staff panel opened" wait_journal 'staff panel opened' 20
sleep 1.5
shot panel
for device in pen board; do
  mark_journal
  dev "$device" unplug
  name=$([ "$device" = pen ] && echo pen || echo switches)
  judge "${device}_unplug_warning" "journalctl -p warning" wait_journal "^warn $name" 20 warning
  journalctl -u "$unit" -p warning --since "@$since" -o cat --no-pager | tail -3
  sleep 1.5
  shot "panel_${device}_lost"
  mark_journal
  dev "$device" plug
  judge "${device}_replug" "journal: back" wait_journal "$name.*back\|$name: ok" 30
  sleep 1.5
  shot "panel_${device}_back"
done
dev chord 2.5
wait_journal 'staff panel closed' 20
sleep 1
# After the replug the pen strokes again and the board switches again.
mark stroke2_down
dev down 0.40 0.40 0.5 10
dev drag 0.55 0.45 1.0 0.5 10
mark stroke2_lift
dev up
sleep 3
mark stroke2_quiet
mark_journal
dev token 4 on
judge board_after_replug "journal: showing cracked_ground" wait_journal 'showing cracked_ground' 20
dev token 4 off
kill "$capture_pid" 2>/dev/null
wait "$capture_pid" 2>/dev/null

# --- 8. the package's life: upgrade keeps config and counters, remove keeps them, purge not
config=/etc/sketch-a-scratch/kiosk.toml
sha_config=$(sha256sum <"$config")
cp "$counters" "$out/counters-before-upgrade.toml"
apt-get install -y -q "$share/pkg/newer.deb" >"$out/upgrade.log" 2>&1
judge upgrade_installed "$(dpkg-query -W -f='${Version}' sketch-a-scratch)" \
  test "$(dpkg-query -W -f='${Version}' sketch-a-scratch)" = "$(cat "$share/pkg/newer.version")"
judge upgrade_keeps_config "sha256" test "$(sha256sum <"$config")" = "$sha_config"
judge upgrade_keeps_counters "sessions $(visits "$out/counters-before-upgrade.toml") -> $(visits "$counters")" \
  test "$(visits "$counters")" -ge "$(visits "$out/counters-before-upgrade.toml")"
for _ in $(seq 300); do active && break; sleep 0.1; done
judge upgrade_restarts_kiosk "state $(systemctl show -p ActiveState --value $unit)" active
apt-get remove -y -q sketch-a-scratch >"$out/remove.log" 2>&1
judge remove_keeps_config "$config" test -f "$config"
judge remove_keeps_counters "$counters" test -f "$counters"
judge remove_removes_binary "/usr/bin/sketch-a-scratch" test ! -e /usr/bin/sketch-a-scratch
judge remove_stops_kiosk "state $(systemctl show -p ActiveState --value $unit)" bash -c '! systemctl is-active -q sketch-a-scratch'
apt-get purge -y -q sketch-a-scratch >"$out/purge.log" 2>&1
judge purge_removes_config "/etc/sketch-a-scratch" test ! -e /etc/sketch-a-scratch
judge purge_removes_state "/var/lib/sketch-a-scratch" test ! -e /var/lib/sketch-a-scratch
judge purge_removes_user "sas-kiosk" bash -c '! getent passwd sas-kiosk >/dev/null'
log "visitor done"

# Shared by the Xvfb end-to-end scripts (sourced, not run).
# Stops a background process: SIGTERM, then SIGKILL if it is still there after 3 s (an Xvfb whose
# last client died under a sanitizer has been seen to sit on SIGTERM for minutes).
stop_pid() {
  kill "$1" 2>/dev/null || return 0
  for _ in $(seq 30); do kill -0 "$1" 2>/dev/null || break; sleep 0.1; done
  kill -9 "$1" 2>/dev/null || true
  wait "$1" 2>/dev/null || true
}
# Sanitizer builds: LeakSanitizer would turn the exit status into 1 for the blocks Mesa's and
# D-Bus's libraries keep until exit (unnamed modules no suppression can match); leaks in our code
# are the unit tests' business.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"

# Waiting. A step waits for its event (a log line, a screen that shows what it must, a file's
# size), never for a fixed time: on a busy machine (CI, a packager's build) everything takes
# several times longer, and a fixed pause then checks too early. The deadline is only there for
# a step that never comes, so it is generous; each wait says how long it took.
e2e_wait_s=${SAS_E2E_WAIT_S:-120}
now_ms() { echo $(($(date +%s%N) / 1000000)); }
seconds_since() {  # seconds_since <now_ms at the start>: "1.234"
  local ms=$(($(now_ms) - $1))
  printf '%d.%03d' $((ms / 1000)) $((ms % 1000))
}
# until_true <what> <command...>: runs the command every 0.1 s until it succeeds, then prints
# "wait: <what>: <seconds> s [(<n> tries)]". Gives up after $e2e_wait_s, or as soon as the process whose pid is
# in $watch has ended (the event can no longer come; one last try first).
until_true() {
  local what=$1 t0 tries=1
  shift
  t0=$(now_ms)
  until "$@"; do
    if [ -n "${watch:-}" ] && ! kill -0 "$watch" 2>/dev/null; then
      "$@" && break
      echo "wait: $what: the process ended ($(seconds_since "$t0") s, $tries tries)"
      return 1
    fi
    if [ $(($(now_ms) - t0)) -ge $((e2e_wait_s * 1000)) ]; then
      echo "wait: $what: not within ${e2e_wait_s} s ($tries tries)"
      return 1
    fi
    tries=$((tries + 1))
    sleep 0.1
  done
  if [ $tries = 1 ]; then
    echo "wait: $what: $(seconds_since "$t0") s"
  else
    echo "wait: $what: $(seconds_since "$t0") s ($tries tries)"
  fi
}
# shot_until <name> <what> <check...>: screenshots of the root window into $work/<name>.png until
# the check (a command reading that file) passes on one. A screen shows a change a few frames
# after the app logged it (a cross-fade, a veil fading out, the next frame on a busy machine), so
# a single screenshot at a guessed moment races. The check's output for the shot that passed (or
# the last one) is printed.
shot_until() {
  local name=$1 what=$2
  shift 2
  local status=0
  until_true "screen shows $what" _shot_shows "$name" "$@" || status=1
  cat "$work/$name.check" 2>/dev/null
  return $status
}
_shot_shows() {
  local name=$1
  shift
  import -window root "$work/$name.png" 2>"$work/$name.check" || return 1
  "$@" >"$work/$name.check" 2>&1
}
# start_xvfb <width> <height>: Xvfb on a free display (it writes the number to fd 3), DISPLAY set,
# its pid in xvfb_pid.
start_xvfb() {
  Xvfb -displayfd 3 -screen 0 "${1}x${2}x24" -nolisten tcp 3>"$work/display" 2>"$work/xvfb.log" &
  xvfb_pid=$!
  local watch=$xvfb_pid
  until_true "Xvfb's display number" test -s "$work/display" || {
    cat "$work/xvfb.log"
    return 1
  }
  export DISPLAY=":$(cat "$work/display")"
}

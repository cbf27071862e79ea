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

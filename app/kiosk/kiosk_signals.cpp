// The kiosk process's signals (see kiosk_signals.h).
#include "kiosk/kiosk_signals.h"

#include <atomic>
#include <csignal>

namespace sas::kiosk {
namespace {

std::atomic<bool> g_stop{false};
std::atomic<bool> g_hangup{false};
std::atomic<bool> g_status{false};
static_assert(std::atomic<bool>::is_always_lock_free, "signal handlers need a lock-free flag");

void OnStop(int /*signal*/) {
  g_stop.store(true);
}

void OnHangup(int /*signal*/) {
  g_hangup.store(true);
}

void OnStatus(int /*signal*/) {
  g_status.store(true);
}

// sigaction rather than signal(): the semantics (handler stays, SA_RESTART) are spelled out.
void Handle(int signal, void (*handler)(int)) {
  struct sigaction action {};
  action.sa_handler = handler;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(signal, &action, nullptr);
}

}  // namespace

void CatchHangupAndIgnoreWriteSignals() {
  Handle(SIGHUP, OnHangup);
  Handle(SIGUSR1, OnStatus);
  Handle(SIGPIPE, SIG_IGN);
  Handle(SIGXFSZ, SIG_IGN);
}

void CatchStopSignals() {
  Handle(SIGTERM, OnStop);
  Handle(SIGINT, OnStop);
}

bool StopRequested() {
  return g_stop.load();
}

bool TakeHangupRequest() {
  return g_hangup.exchange(false);
}

bool TakeStatusRequest() {
  return g_status.exchange(false);
}

}  // namespace sas::kiosk

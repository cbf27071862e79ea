#pragma once
// The kiosk process's signals. The handlers only set lock-free atomic flags (async-signal-safe);
// the control loop takes them between passes:
//   SIGTERM, SIGINT  -> stop: the loop ends, the counters are saved, the devices are closed;
//   SIGHUP           -> hangup: the unit's reload. The counters are saved at once and the kiosk
//                       runs on (the configuration is only read at start);
//   SIGUSR1          -> status: one journal line with every device's state and the counts, the
//                       kiosk runs on (its default action would end the process unsaved);
//   SIGPIPE, SIGXFSZ -> ignored: a closed stdout/stderr pipe, a file-size limit or a full disk
//                       fail the write (reported, the kiosk carries on) instead of ending it.

namespace sas::kiosk {

// SIGHUP, SIGUSR1, SIGPIPE and SIGXFSZ: first thing at start, so no early write, reload or status
// request ends the process.
void CatchHangupAndIgnoreWriteSignals();
// SIGTERM and SIGINT: once the kiosk can run its loop; before that their default action ends the
// process at once, with nothing to save yet.
void CatchStopSignals();

bool StopRequested();
// True once per SIGHUP received since the last call (several in between count as one).
bool TakeHangupRequest();
// True once per SIGUSR1 received since the last call.
bool TakeStatusRequest();

}  // namespace sas::kiosk

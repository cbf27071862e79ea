#pragma once
// The open/close callbacks libinput's udev backend calls for each event node: plain open(2) with
// O_CLOEXEC added (the kiosk runs as a user in group `input`, no logind session to ask).

#include <libinput.h>

namespace sas::platform {

const libinput_interface* LibinputOpenInterface();

}  // namespace sas::platform

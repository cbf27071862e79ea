// Tablet discovery through libinput + udev (see tablet_devices.h).
#include "platform/pen/tablet_devices.h"

#include "platform/pen/libinput_open.h"

#include <libinput.h>
#include <libudev.h>

namespace sas::platform {

std::vector<TabletInfo> ListTablets(std::string* error) {
  std::vector<TabletInfo> tablets;
  udev* udev_context = udev_new();
  if (udev_context == nullptr) {
    if (error) *error = "udev unavailable";
    return tablets;
  }
  libinput* input = libinput_udev_create_context(LibinputOpenInterface(), nullptr, udev_context);
  if (input == nullptr) {
    udev_unref(udev_context);
    if (error) *error = "libinput context failed";
    return tablets;
  }
  if (libinput_udev_assign_seat(input, "seat0") != 0) {
    if (error) *error = "cannot assign seat0 (no udev, or no permission on /dev/input)";
  } else {
    libinput_dispatch(input);
    while (libinput_event* event = libinput_get_event(input)) {
      if (libinput_event_get_type(event) == LIBINPUT_EVENT_DEVICE_ADDED) {
        libinput_device* device = libinput_event_get_device(event);
        if (libinput_device_has_capability(device, LIBINPUT_DEVICE_CAP_TABLET_TOOL)) {
          tablets.push_back(
              {libinput_device_get_name(device), libinput_device_get_sysname(device)});
        }
      }
      libinput_event_destroy(event);
    }
  }
  libinput_unref(input);
  udev_unref(udev_context);
  return tablets;
}

void ReportTablets(DeviceReport& report) {
  std::string error;
  const auto tablets = ListTablets(&error);
  if (tablets.empty()) {
    report.push_back({"pen", false,
                      "no pen tablet" + (error.empty() ? std::string() : " (" + error + ")") +
                          ": mouse/touch fallback (no pressure or tilt)"});
  }
  for (const auto& tablet : tablets) {
    report.push_back({"pen", true, tablet.name + " (" + tablet.sysname + ")"});
  }
}

}  // namespace sas::platform

// MCP2221A discovery through hidapi (see hid_devices.h).
#include "platform/hid/hid_devices.h"

#include <hidapi/hidapi.h>

namespace sas::platform {
namespace {

std::string Narrow(const wchar_t* text) {
  std::string out;
  if (text == nullptr) return out;
  for (; *text != L'\0'; ++text) out.push_back(*text < 128 ? static_cast<char>(*text) : '?');
  return out;
}

}  // namespace

std::vector<HidDeviceInfo> ListMcp2221Adapters() {
  std::vector<HidDeviceInfo> adapters;
  if (hid_init() != 0) return adapters;
  hid_device_info* list = hid_enumerate(kMcp2221VendorId, kMcp2221ProductId);
  for (hid_device_info* it = list; it != nullptr; it = it->next) {
    adapters.push_back(
        {it->path ? it->path : "", Narrow(it->product_string), Narrow(it->serial_number)});
  }
  hid_free_enumeration(list);
  hid_exit();
  return adapters;
}

void ReportHidAdapters(DeviceReport& report) {
  const auto adapters = ListMcp2221Adapters();
  if (adapters.empty()) {
    report.push_back({"hid", false, "no MCP2221A USB GPIO adapter (04d8:00dd)"});
  }
  for (const auto& adapter : adapters) {
    report.push_back({"hid", true, "MCP2221A at " + adapter.path + " serial " + adapter.serial});
  }
}

}  // namespace sas::platform

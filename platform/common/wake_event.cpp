#include "platform/common/wake_event.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cstdint>

namespace sas::platform {

bool WakeEvent::Open() {
  Close();
  fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  return fd_ >= 0;
}

void WakeEvent::Signal() {
  if (fd_ < 0) return;
  const std::uint64_t one = 1;
  // A full counter (never reached here) would fail the write; the poller is awake either way.
  [[maybe_unused]] const ssize_t n = write(fd_, &one, sizeof one);
}

void WakeEvent::Close() {
  if (fd_ >= 0) close(fd_);
  fd_ = -1;
}

}  // namespace sas::platform

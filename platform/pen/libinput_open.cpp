#include "platform/pen/libinput_open.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

namespace sas::platform {
namespace {

int OpenRestricted(const char* path, int flags, void* /*user_data*/) {
  const int fd = open(path, flags | O_CLOEXEC);
  return fd < 0 ? -errno : fd;
}

void CloseRestricted(int fd, void* /*user_data*/) {
  close(fd);
}

constexpr libinput_interface kInterface = {OpenRestricted, CloseRestricted};

}  // namespace

const libinput_interface* LibinputOpenInterface() {
  return &kInterface;
}

}  // namespace sas::platform

#pragma once
// For one test: a datagram socket standing in for systemd's notify socket (NOTIFY_SOCKET points at
// it while the object lives), so what the process tells systemd (READY=1, WATCHDOG=1, STATUS=) can
// be read back in the order it was sent.
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/temp_dir.h"

namespace sas::test {

class NotifySocket {
 public:
  NotifySocket() {
    const std::string path = dir_.file("notify.sock");
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    if (fd_ < 0) throw std::runtime_error("notify socket: socket() failed");
    sockaddr_un addr{};
    addr.sun_family = AF_UNIX;
    if (path.size() >= sizeof addr.sun_path) throw std::runtime_error("notify socket: long path");
    std::copy(path.begin(), path.end(), addr.sun_path);
    if (bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
      close(fd_);
      throw std::runtime_error("notify socket: bind() failed");
    }
    setenv("NOTIFY_SOCKET", path.c_str(), 1);
  }
  ~NotifySocket() {
    unsetenv("NOTIFY_SOCKET");
    close(fd_);
  }
  NotifySocket(const NotifySocket&) = delete;
  NotifySocket& operator=(const NotifySocket&) = delete;

  // Every message received since the last call, oldest first (never blocks).
  std::vector<std::string> Drain() {
    std::vector<std::string> out;
    char buf[4096];
    for (;;) {
      const ssize_t n = recv(fd_, buf, sizeof buf, 0);
      if (n <= 0) break;
      out.emplace_back(buf, static_cast<std::size_t>(n));
    }
    return out;
  }

 private:
  TempDir dir_;
  int fd_ = -1;
};

}  // namespace sas::test

#pragma once
// Limits the size of files this process may write for a scope, as a full disk would: RLIMIT_FSIZE
// fails writes with EFBIG as a full disk fails them with ENOSPC, and works as root (a read-only
// folder does not). SIGXFSZ is ignored meanwhile, so the write fails instead of killing the test.

#include <sys/resource.h>

#include <csignal>

namespace sas::test {

class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

}  // namespace sas::test

// Logger (see log.h).
#include "platform/log/log.h"

#include <fcntl.h>
#include <unistd.h>

#include "platform/common/clock.h"

namespace sas::platform {

const char* LogLevelName(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug:
      return "debug";
    case LogLevel::kInfo:
      return "info";
    case LogLevel::kWarn:
      return "warn";
    case LogLevel::kError:
      return "error";
  }
  return "?";
}

std::string LogLine::Text() const {
  return std::string(LogLevelName(level)) + " " + component + ": " + message;
}

Logger::Logger(std::size_t ring_capacity)
    : capacity_(ring_capacity), out_fd_(fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3)) {}

Logger::~Logger() {
  if (out_fd_ >= 0) close(out_fd_);
}

void Logger::Write(LogLevel level, std::string_view component, std::string_view message) {
  LogLine line{MonotonicNowNs(), level, std::string(component), std::string(message)};
  std::lock_guard lock(mutex_);
  if (level < min_level_) return;
  if (echo_) {
    // One write() per line (under our mutex) so lines never interleave mid-line.
    const std::string text = line.Text() + "\n";
    const int fd = out_fd_ >= 0 ? out_fd_ : STDERR_FILENO;
    [[maybe_unused]] const ssize_t n = write(fd, text.data(), text.size());
  }
  ++count_;
  ring_.push_back(std::move(line));
  while (ring_.size() > capacity_) ring_.pop_front();
}

void Logger::SetMinLevel(LogLevel level) {
  std::lock_guard lock(mutex_);
  min_level_ = level;
}

void Logger::SetEchoToStderr(bool echo) {
  std::lock_guard lock(mutex_);
  echo_ = echo;
}

std::vector<LogLine> Logger::Recent() const {
  std::lock_guard lock(mutex_);
  return {ring_.begin(), ring_.end()};
}

std::uint64_t Logger::Count() const {
  std::lock_guard lock(mutex_);
  return count_;
}

void Logger::Clear() {
  std::lock_guard lock(mutex_);
  ring_.clear();
}

Logger& DefaultLogger() {
  static Logger logger;
  return logger;
}

}  // namespace sas::platform

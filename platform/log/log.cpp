// Logger (see log.h).
#include "platform/log/log.h"

#include <cstdio>

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

void Logger::Write(LogLevel level, std::string_view component, std::string_view message) {
  LogLine line{MonotonicNowNs(), level, std::string(component), std::string(message)};
  std::lock_guard lock(mutex_);
  if (level < min_level_) return;
  if (echo_) {
    // One fprintf per line so lines from different threads never interleave mid-line.
    const std::string text = line.Text();
    std::fprintf(stderr, "%s\n", text.c_str());
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

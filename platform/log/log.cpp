// Logger (see log.h).
#include "platform/log/log.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/uio.h>
// The call site would always be SendToJournal itself: leave CODE_FILE/LINE/FUNC out.
#define SD_JOURNAL_SUPPRESS_LOCATION
#include <systemd/sd-journal.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdlib>
#include <cstring>

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

int JournalPriority(LogLevel level) {
  switch (level) {
    case LogLevel::kDebug:
      return 7;  // LOG_DEBUG
    case LogLevel::kInfo:
      return 6;  // LOG_INFO
    case LogLevel::kWarn:
      return 4;  // LOG_WARNING
    case LogLevel::kError:
      return 3;  // LOG_ERR
  }
  return 6;
}

bool StderrIsJournal(const char* journal_stream, std::uint64_t dev, std::uint64_t ino) {
  if (journal_stream == nullptr) return false;
  const char* end = journal_stream + std::strlen(journal_stream);
  std::uint64_t want_dev = 0, want_ino = 0;
  const auto first = std::from_chars(journal_stream, end, want_dev);
  if (first.ec != std::errc() || first.ptr == end || *first.ptr != ':') return false;
  const auto second = std::from_chars(first.ptr + 1, end, want_ino);
  if (second.ec != std::errc() || second.ptr != end) return false;
  return want_dev == dev && want_ino == ino;
}

std::vector<std::string> JournalFields(const LogLine& line, std::string_view identifier) {
  return {"MESSAGE=" + line.Text(), "PRIORITY=" + std::to_string(JournalPriority(line.level)),
          "SAS_COMPONENT=" + line.component, "SYSLOG_IDENTIFIER=" + std::string(identifier)};
}

int SendToJournal(const std::vector<std::string>& fields) {
  std::vector<iovec> iov(fields.size());
  for (std::size_t i = 0; i < fields.size(); ++i) {
    iov[i].iov_base = const_cast<char*>(fields[i].data());
    iov[i].iov_len = fields[i].size();
  }
  return sd_journal_sendv(iov.data(), static_cast<int>(iov.size()));
}

namespace {

bool StderrIsTheJournal() {
  struct stat st {};
  if (fstat(STDERR_FILENO, &st) != 0) return false;
  return StderrIsJournal(std::getenv("JOURNAL_STREAM"), static_cast<std::uint64_t>(st.st_dev),
                         static_cast<std::uint64_t>(st.st_ino));
}

}  // namespace

Logger::Logger(std::size_t ring_capacity)
    : capacity_(ring_capacity), out_fd_(fcntl(STDERR_FILENO, F_DUPFD_CLOEXEC, 3)) {
  if (StderrIsTheJournal()) journal_ = SendToJournal;
}

Logger::~Logger() {
  if (out_fd_ >= 0) close(out_fd_);
}

void Logger::Write(LogLevel level, std::string_view component, std::string_view message) {
  LogLine line{MonotonicNowNs(), level, std::string(component), std::string(message)};
  std::lock_guard lock(mutex_);
  if (level < min_level_) return;
  // A journal entry that was refused (journald restarting, say) still goes out as a plain line.
  const bool sent =
      echo_ && journal_ && journal_(JournalFields(line, program_invocation_short_name)) >= 0;
  if (echo_ && !sent) {
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

bool Logger::ToJournal() const {
  std::lock_guard lock(mutex_);
  return static_cast<bool>(journal_);
}

void Logger::SetJournalSender(JournalSender sender) {
  std::lock_guard lock(mutex_);
  journal_ = std::move(sender);
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

#pragma once
// The kiosk's log: one clear line per event on stderr (systemd's journal captures it) and an
// in-memory ring of the most recent lines for the staff panel. Usable from every layer's control
// code; never from the audio callback (it formats strings and takes a mutex) — the audio side
// publishes counters instead and the control thread logs their changes.
//
// Line format: "<level> <component>: <message>", e.g. "warn gpio: chip gpiochip0 absent; token
// switches fall back to keys 1-4". The journal adds the time stamp; the ring keeps its own.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace sas::platform {

enum class LogLevel { kDebug = 0, kInfo = 1, kWarn = 2, kError = 3 };

const char* LogLevelName(LogLevel level);

struct LogLine {
  std::int64_t time_ns = 0;  // CLOCK_MONOTONIC
  LogLevel level = LogLevel::kInfo;
  std::string component;
  std::string message;
  std::string Text() const;  // "<level> <component>: <message>"
};

class Logger {
 public:
  explicit Logger(std::size_t ring_capacity = 256);
  ~Logger();
  Logger(const Logger&) = delete;
  Logger& operator=(const Logger&) = delete;

  void Write(LogLevel level, std::string_view component, std::string_view message);
  void Debug(std::string_view c, std::string_view m) { Write(LogLevel::kDebug, c, m); }
  void Info(std::string_view c, std::string_view m) { Write(LogLevel::kInfo, c, m); }
  void Warn(std::string_view c, std::string_view m) { Write(LogLevel::kWarn, c, m); }
  void Error(std::string_view c, std::string_view m) { Write(LogLevel::kError, c, m); }

  // Lines below this level are dropped (neither printed nor kept).
  void SetMinLevel(LogLevel level);
  // Tests and the headless tools may silence stderr and read the ring only.
  void SetEchoToStderr(bool echo);

  // The most recent lines, oldest first (copy: safe to hand to the UI thread).
  std::vector<LogLine> Recent() const;
  // Total lines written since start (including those that left the ring).
  std::uint64_t Count() const;
  void Clear();

 private:
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::deque<LogLine> ring_;
  std::uint64_t count_ = 0;
  LogLevel min_level_ = LogLevel::kInfo;
  bool echo_ = true;
  // A private duplicate of stderr taken at construction: PortAudio's start-up mutes fd 2 for a
  // moment (portaudio_session.h), and our lines from other threads must not vanish meanwhile.
  int out_fd_ = -1;
};

// The process-wide logger the platform backends write to unless given another one.
Logger& DefaultLogger();

}  // namespace sas::platform

#pragma once
// The kiosk's log: one clear line per event on stderr (systemd's journal captures it) and an
// in-memory ring of the most recent lines for the staff panel. Usable from every layer's control
// code; never from the audio callback (it formats strings and takes a mutex) — the audio side
// publishes counters instead and the control thread logs their changes.
//
// Line format: "<level> <component>: <message>", e.g. "warn gpio: chip gpiochip0 absent; token
// switches fall back to keys 1-4". The journal adds the time stamp; the ring keeps its own.
//
// Under systemd with StandardError=journal every stderr line would reach the journal at the
// stream's one priority (info), so `journalctl -p warning` would miss a failing device. When
// stderr is the journal (systemd's documented check: $JOURNAL_STREAM = "<dev>:<inode>" of fd 2)
// each line is sent as a native journal entry instead: the same text as MESSAGE, PRIORITY from
// the level, SAS_COMPONENT and SYSLOG_IDENTIFIER. If the journal refuses an entry the plain line
// goes to stderr as before. Anywhere else (a terminal, the tests, the headless tools reading
// stderr) the plain lines are unchanged.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
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

// The journal's priority (syslog level) for a level: error 3, warn 4, info 6, debug 7.
int JournalPriority(LogLevel level);

// True when `journal_stream` (the value of $JOURNAL_STREAM, may be null) names the file with
// device `dev` and inode `ino` (fstat of fd 2). systemd sets the variable when it connects stderr
// to the journal; a process whose stderr was redirected since inherits it but no longer matches.
bool StderrIsJournal(const char* journal_stream, std::uint64_t dev, std::uint64_t ino);

// The fields of one journal entry for `line`: "MESSAGE=<level> <component>: <message>",
// "PRIORITY=<n>", "SAS_COMPONENT=<component>" and "SYSLOG_IDENTIFIER=<identifier>".
std::vector<std::string> JournalFields(const LogLine& line, std::string_view identifier);

// Sends one entry's fields; returns 0 when the journal took it, a negative errno otherwise.
using JournalSender = std::function<int(const std::vector<std::string>& fields)>;
// The real sender: libsystemd's sd_journal_sendv.
int SendToJournal(const std::vector<std::string>& fields);

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
  // Tests and the headless tools may silence stderr and read the ring only (this silences the
  // journal entries too).
  void SetEchoToStderr(bool echo);
  // True when lines go to the journal as entries with their priority (stderr was the journal
  // when the logger was made).
  bool ToJournal() const;
  // Sends lines through `sender` as if stderr were the journal (tests); null: plain stderr.
  void SetJournalSender(JournalSender sender);

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
  JournalSender journal_;  // set when stderr is the journal
};

// The process-wide logger the platform backends write to unless given another one.
Logger& DefaultLogger();

}  // namespace sas::platform

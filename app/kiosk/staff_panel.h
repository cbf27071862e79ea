#pragma once
// The staff panel's logic (control thread): what it says and what its buttons do. The panel opens
// over the picture on the staff chord (Session decides when it is open). It lists the version,
// every device's status (with the output's xruns, the microphone's level, the tokens), the audio
// load, the pen-to-sound latency, the pen, the usage counters, the speaker's dose, the
// configuration in use and the journal's last lines, and has one row of buttons under captions
// that say what they work on and its state: test tone, transducer sweep, low-vibration mode,
// volume and vibration steps. The drawing (text layout, button rectangles) belongs to the app's
// staff panel view; nothing here knows pixels beyond the pen's position it reports.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kiosk/kiosk_engine.h"
#include "platform/audio/audio_output.h"
#include "platform/device_status.h"
#include "platform/input/switch_factory.h"
#include "platform/input/token_selector.h"
#include "platform/log/log.h"
#include "platform/pen/pen_reading.h"

namespace sas::kiosk {

// The buttons, in their order along the panel's bottom edge.
enum class StaffButton {
  kTone,
  kSweep,
  kLowVibration,
  kVolumeDown,
  kVolumeUp,
  kVibrationDown,
  kVibrationUp,
  kCount
};
inline constexpr int kStaffButtonCount = static_cast<int>(StaffButton::kCount);

// A button's label: what it does ("Turn on", "+3 dB"); the caption above it says what it works
// on and the state now.
const char* StaffButtonLabel(StaffButton button, bool low_vibration);

// A caption over the buttons from `first` to `last`: "Low vibration: off", "Volume: +3 dB".
struct StaffButtonCaption {
  StaffButton first, last;
  std::string text;
  bool operator==(const StaffButtonCaption&) const = default;
};
std::vector<StaffButtonCaption> StaffButtonCaptions(const KioskEngine& engine);

// What the panel reports on, read when its text is rebuilt.
struct StaffPanelInputs {
  const KioskEngine* engine;
  const platform::AudioOutput* output;
  const platform::DeviceStatusBoard* board;  // its logger's ring: the journal's last lines
  const platform::SwitchInputs* switches;
  const platform::TokenSelector* selector;
  bool record_down;
  platform::PenReading pen;  // the last reading, from whichever input
  std::string config_line;   // ConfigStatusLine
  int buffer_frames;
  int sample_rate_hz;
};

// One line of the panel's text; `warning` lines (the title, a device not ok) stand out.
// `journal` lines are the journal's last lines, as it has them: the view keeps the newest that
// fit.
struct StaffPanelLine {
  std::string text;
  bool warning = false;
  bool journal = false;
  bool operator==(const StaffPanelLine&) const = default;
};

// How many of the journal's last lines the text ends with (the board's logger's ring).
inline constexpr std::size_t kStaffJournalLines = 8;

// The panel's text, top to bottom: the title; one line per device and start-up check (its name,
// the journal's name, state, backend, message, and the output's xruns, the microphone's level,
// the tokens and the record button, what is shown); the audio load; pen to sound; the pen; the
// usage counters; the speaker's Leq; the configuration file (accepted, or which copy runs) and
// its key values in use; the journal's last lines.
std::vector<StaffPanelLine> StaffPanelLines(const StaffPanelInputs& in);

// An equivalent level for the panel: "-20.3 dBFS", "silent" below kSilentLeqDbfs (a visit with no
// sound measures the meter's floor, which would read as a number nobody can use), "-" with none.
inline constexpr double kSilentLeqDbfs = -100.0;
std::string LeqText(std::optional<double> dbfs);

// The buttons' actions. A press repeats only after kRepeatNs, so a pen resting on a button does not
// step the volume at the pen's report rate.
class StaffPanel {
 public:
  static constexpr std::int64_t kRepeatNs = 500'000'000;

  // The pen pressed `button` at `time_ns`: the engine acts (and restarts the panel's timeout) and
  // the journal gets one line. False when ignored as a repeat.
  bool Press(StaffButton button, std::int64_t time_ns, KioskEngine& engine, platform::Logger& log);

 private:
  std::int64_t last_press_ns_ = 0;
};

}  // namespace sas::kiosk

// The staff panel's text and button actions (see staff_panel.h).
#include "kiosk/staff_panel.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <optional>

#include "common/text.h"
#include "files/contact_scheme_names.h"
#include "sas/version.h"
#include "synth/contact.h"

namespace sas::kiosk {
namespace {

using text::Fixed;

// "3 %": a share in whole percent, one decimal below 10 % (a light load still reads as moving).
std::string Percent(double share) {
  return Fixed(100.0 * share, 100.0 * share < 10.0 ? 1 : 0) + " %";
}

// The callback's time budget is one buffer's duration: a callback that takes longer than that
// is late, and the device plays a gap (an xrun). The mean and the recent peak leave out the
// warm-up after the stream opens (audio_output.h), which the old maximum since the start kept:
// a single 60 ms first callback read as "max 2237 %" for the whole run.
std::string AudioLoadLine(const StaffPanelInputs& in) {
  const double buffer_ms = 1e3 * in.buffer_frames / in.sample_rate_hz;
  std::string line = "Audio load: ";
  if (!in.output->Running()) return line + "none (no sound output)";
  const auto stats = in.output->Stats();
  const double budget_ns = buffer_ms * 1e6;
  return line + Percent(static_cast<double>(stats.mean_callback_ns) / budget_ns) +
         " of the time budget, peak " +
         Percent(static_cast<double>(stats.recent_max_callback_ns) / budget_ns) +
         " in the last 20 s (budget " + Fixed(buffer_ms, 2) +
         " ms a callback: " + std::to_string(in.buffer_frames) + " frames at " +
         std::to_string(in.sample_rate_hz) + " Hz; over 100 % the sound breaks up)";
}

std::string LatencyLine(const StaffPanelInputs& in) {
  const double buffer_ms = 1e3 * in.buffer_frames / in.sample_rate_hz;
  const auto stats = in.engine->audio_stats();
  return "Pen to sound: last " + Fixed(static_cast<double>(stats.pen_to_sample_last_ns) * 1e-6, 2) +
         " ms, slowest " + Fixed(static_cast<double>(stats.pen_to_sample_max_ns) * 1e-6, 2) +
         " ms (target " + Fixed(buffer_ms + 1.0, 2) + " ms), readings dropped " +
         std::to_string(stats.dropped_commands);
}

// The dose, for staff (the README's staff guide turns it into dB SPL with a phone meter once).
std::string DoseLine(const KioskEngine& engine) {
  return "Speaker Leq: last visit " + LeqText(engine.exposure().LastVisitDb()) + ", last hour " +
         LeqText(engine.exposure().LastHourDb()) + " (speaker ceiling " +
         Fixed(engine.config().sound_ceiling_db, 1) + " dBTP)";
}

// What each board entry is called on the panel; the journal's name follows in brackets, so a
// line can be found in `journalctl` as it reads there.
std::string DeviceName(const std::string& key) {
  if (key == "audio_out") return "Sound output";
  if (key == "audio_in") return "Microphone";
  if (key == "pen") return "Pen tablet";
  if (key == "switches") return "Token switches";
  if (key == "textures") return "Textures";
  if (key == "storage") return "Storage";
  if (key == "display") return "Display";
  std::string name = key;
  if (!name.empty()) name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
  return name;
}

// What a device's line adds to its state: the output's xruns, the microphone's level, the
// tokens and the record button, what the screen shows.
std::string DeviceDetails(const StaffPanelInputs& in, const platform::DeviceStatus& status) {
  const KioskEngine& engine = *in.engine;
  if (status.device == "audio_out") {
    return "; xruns " + std::to_string(in.output->Stats().xruns);
  }
  if (status.device == "audio_in") {
    const float level = engine.mic_level();
    if (!engine.recorder_present()) return "";
    return "; level " + (level > 0.0f ? Fixed(20.0 * std::log10(level), 1) : "-inf") + " dBFS";
  }
  if (status.device == "switches") {
    std::string on;
    for (int t = 0; t < platform::kTokenCount; ++t) {
      if (in.selector->Present(t)) on += (on.empty() ? "" : ", ") + std::to_string(t + 1);
    }
    return "; tokens on: " + (on.empty() ? std::string("none") : on) + ", record button " +
           (in.record_down ? "down" : "up");
  }
  if (status.device == "textures") {
    return "; showing " +
           (engine.surface().voice
                ? std::string("the voice")
                : engine.textures()[static_cast<std::size_t>(engine.surface().texture)].key) +
           ", language " + engine.language() + ", " + std::to_string(engine.cues_loaded()) +
           " spoken cues" +
           (engine.staff_cues_loaded() > 0
                ? " (" + std::to_string(engine.staff_cues_loaded()) + " staff-recorded)"
                : "");
  }
  return "";
}

std::string PenLine(const platform::PenReading& pen) {
  return "Pen: pressure " + Fixed(pen.pressure, 2) + ", tilt " + Fixed(pen.TiltDeg(), 1) +
         " deg, at " + Fixed(pen.x_px, 0) + "," + Fixed(pen.y_px, 0) +
         (pen.origin == platform::PenOrigin::kTablet  ? " (tablet)"
          : pen.origin == platform::PenOrigin::kTouch ? " (touch)"
                                                      : " (mouse)");
}

std::string UsageLine(const KioskEngine& engine) {
  const auto& counters = engine.session().counters();
  std::string line = "Usage: visits " + std::to_string(counters.sessions) + ", recordings " +
                     std::to_string(counters.recordings) + " (" +
                     std::to_string(counters.failed_recordings) + " failed), strokes:";
  for (std::size_t t = 0; t < counters.strokes_per_texture.size(); ++t) {
    line += " " + engine.textures()[t].key + " " + std::to_string(counters.strokes_per_texture[t]) +
            ",";
  }
  return line + " voice " + std::to_string(counters.voice_strokes);
}

std::string Db(double value) {
  return (value > 0.0 ? "+" : "") + Fixed(value, value == std::round(value) ? 0 : 1) + " dB";
}

// The configuration's key values in use (whichever copy they came from).
// What each texture's contact runs: the scheme and the adaptive sub-steps' range at 48 kHz,
// chosen by contact_bench from the error budget (files/contact_choice.h) or built in.
std::string ContactLine(const KioskEngine& engine) {
  std::string text = "Contact (contact_bench's choice, docs/contact-budget.md):";
  for (const auto& t : engine.textures()) {
    const auto& p = t.material.params;
    const int most = synth::ChooseContactOversample(p.impact, p.probe.mass_kg, 48000.0);
    text += " " + t.key + " " + ContactSchemeName(p.impact.scheme) + " x1-" +
            std::to_string(most) +
            (!t.material.contact_from_benchmark ? " (built-in);"
             : t.material.contact_budget_met    ? ";"
                                                : " (budget not met);");
  }
  if (text.back() == ';') text.pop_back();
  return text;
}

std::string InUseLine(const KioskConfig& c) {
  std::string languages;
  for (const auto& code : c.visitor_languages) languages += (languages.empty() ? "" : " ") + code;
  return "In use: output '" + c.output_device + "', microphone '" + c.input_device + "', " +
         std::to_string(c.sample_rate_hz) + " Hz, " + std::to_string(c.buffer_frames) +
         " frames; sound " + Db(c.sound_gain_db) + ", vibration " + Db(c.haptic_gain_db) +
         ", low vibration " + Db(-c.low_vibration_db) + "; switches " + c.switches_backend +
         "; idle reset " + Fixed(c.idle_timeout_s, 0) + " s; language " + c.language +
         " (choices: " + (languages.empty() ? std::string("none") : languages) + ")";
}

void LogGains(const KioskEngine& engine, platform::Logger& log) {
  const auto& staff = engine.staff_settings();
  log.Info("staff", "volume " + Fixed(staff.volume_db, 0) + " dB, vibration " +
                        Fixed(staff.vibration_db, 0) + " dB");
}

}  // namespace

const char* StaffButtonLabel(StaffButton button, bool low_vibration) {
  switch (button) {
    case StaffButton::kTone:
      return "Test tone";
    case StaffButton::kSweep:
      return "Sweep";
    case StaffButton::kLowVibration:
      return low_vibration ? "Turn off" : "Turn on";
    case StaffButton::kVolumeDown:
    case StaffButton::kVibrationDown:
      return "-3 dB";
    case StaffButton::kVolumeUp:
    case StaffButton::kVibrationUp:
      return "+3 dB";
    case StaffButton::kCount:
      break;
  }
  return "";
}

std::vector<StaffButtonCaption> StaffButtonCaptions(const KioskEngine& engine) {
  const auto& staff = engine.staff_settings();
  return {
      {StaffButton::kTone, StaffButton::kSweep, "Test signals"},
      {StaffButton::kLowVibration, StaffButton::kLowVibration,
       std::string("Low vibration: ") + (engine.low_vibration() ? "on" : "off")},
      {StaffButton::kVolumeDown, StaffButton::kVolumeUp, "Volume: " + Db(staff.volume_db)},
      {StaffButton::kVibrationDown, StaffButton::kVibrationUp,
       "Vibration: " + Db(staff.vibration_db)},
  };
}

std::string LeqText(std::optional<double> dbfs) {
  if (!dbfs) return "-";
  if (*dbfs < kSilentLeqDbfs) return "silent";
  return Fixed(*dbfs, 1) + " dBFS";
}

std::vector<StaffPanelLine> StaffPanelLines(const StaffPanelInputs& in) {
  const KioskEngine& engine = *in.engine;
  std::vector<StaffPanelLine> lines;
  lines.push_back({std::string("Sketch-a-Scratch ") + kVersion +
                       " - staff panel (the staff chord again closes it)",
                   true});
  lines.push_back({ContactLine(engine)});
  bool config_ok = true;
  for (const auto& status : in.board->All()) {
    // The configuration has a line of its own below (which copy runs, and its values).
    if (status.device == "config") {
      config_ok = status.state == platform::DeviceState::kOk;
      continue;
    }
    lines.push_back({DeviceName(status.device) + " (" + status.device +
                         "): " + platform::DeviceStateName(status.state) +
                         (status.backend.empty() ? "" : " (" + status.backend + ")") + ": " +
                         status.message + DeviceDetails(in, status),
                     status.state != platform::DeviceState::kOk});
  }
  lines.push_back({AudioLoadLine(in)});
  lines.push_back({LatencyLine(in)});
  lines.push_back({PenLine(in.pen)});
  lines.push_back({UsageLine(engine)});
  lines.push_back({DoseLine(engine)});
  lines.push_back({in.config_line, !config_ok});
  lines.push_back({InUseLine(engine.config())});
  lines.push_back(
      {"Journal: the last lines, newest at the bottom (journalctl -u sketch-a-scratch)"});
  const auto recent = in.board->logger().Recent();
  const std::size_t first =
      recent.size() > kStaffJournalLines ? recent.size() - kStaffJournalLines : 0;
  for (std::size_t i = first; i < recent.size(); ++i) {
    lines.push_back({recent[i].Text(), false, true});
  }
  return lines;
}

bool StaffPanel::Press(StaffButton button, std::int64_t time_ns, KioskEngine& engine,
                       platform::Logger& log) {
  if (button == StaffButton::kCount || time_ns - last_press_ns_ <= kRepeatNs) return false;
  last_press_ns_ = time_ns;
  engine.OnStaffActivity(time_ns);
  switch (button) {
    case StaffButton::kTone:
      engine.PlayTestTone();
      log.Info("staff", "test tone on the speaker");
      break;
    case StaffButton::kSweep:
      engine.PlayTransducerSweep();
      log.Info("staff", "sweep on the transducer");
      break;
    case StaffButton::kLowVibration:
      engine.SetLowVibration(!engine.low_vibration());
      log.Info("staff",
               engine.low_vibration() ? "low-vibration mode on" : "low-vibration mode off");
      break;
    case StaffButton::kVolumeDown:
    case StaffButton::kVolumeUp:
      engine.StepVolume(button == StaffButton::kVolumeUp ? 1 : -1);
      LogGains(engine, log);
      break;
    case StaffButton::kVibrationDown:
    case StaffButton::kVibrationUp:
      engine.StepVibration(button == StaffButton::kVibrationUp ? 1 : -1);
      LogGains(engine, log);
      break;
    case StaffButton::kCount:
      break;
  }
  return true;
}

}  // namespace sas::kiosk

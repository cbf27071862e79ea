// The staff panel's text and button actions (see staff_panel.h).
#include "kiosk/staff_panel.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "sas/version.h"

namespace sas::kiosk {
namespace {

std::string Fixed(double value, int decimals) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string AudioLine(const StaffPanelInputs& in) {
  const auto stats = in.output->Stats();
  const double buffer_ms = 1e3 * in.buffer_frames / in.sample_rate_hz;
  return "Audio: " + std::string(in.output->Running() ? "running" : "silent (no device)") +
         ", xruns " + std::to_string(stats.xruns) + ", callback load " +
         Fixed(100.0 * static_cast<double>(stats.last_callback_ns) * 1e-6 / buffer_ms, 1) +
         "% (max " +
         Fixed(100.0 * static_cast<double>(stats.max_callback_ns) * 1e-6 / buffer_ms, 1) +
         "%) of " + Fixed(buffer_ms, 2) + " ms";
}

std::string LatencyLine(const StaffPanelInputs& in) {
  const double buffer_ms = 1e3 * in.buffer_frames / in.sample_rate_hz;
  const auto stats = in.engine->audio_stats();
  return "Pen event -> first output sample: last " +
         Fixed(static_cast<double>(stats.pen_to_sample_last_ns) * 1e-6, 2) + " ms, max " +
         Fixed(static_cast<double>(stats.pen_to_sample_max_ns) * 1e-6, 2) + " ms (target " +
         Fixed(buffer_ms + 1.0, 2) + " ms), dropped " + std::to_string(stats.dropped_commands);
}

// The dose, for staff (the README's staff guide turns it into dB SPL with a phone meter once).
std::string DoseLine(const KioskEngine& engine) {
  return "Speaker Leq: last visit " + LeqText(engine.exposure().LastVisitDb()) + ", last hour " +
         LeqText(engine.exposure().LastHourDb()) + " (speaker ceiling " +
         Fixed(engine.config().sound_ceiling_db, 1) + " dBTP)";
}

std::string SwitchesLine(const StaffPanelInputs& in) {
  const KioskEngine& engine = *in.engine;
  std::string line = "Switches: " + std::string(in.switches->ActiveBackend()) + ", tokens";
  for (int t = 0; t < platform::kTokenCount; ++t) {
    line += " " + std::to_string(t + 1) + (in.selector->Present(t) ? ": on" : ": off");
  }
  return line + ", record " + std::string(in.record_down ? "down" : "up") + ", showing " +
         (engine.surface().voice
              ? std::string("the voice")
              : engine.textures()[static_cast<std::size_t>(engine.surface().texture)].key) +
         ", language " + engine.language();
}

std::string MicrophoneLine(const KioskEngine& engine) {
  const float level = engine.mic_level();
  return "Microphone: " +
         std::string(engine.recorder_present()
                         ? "level " + (level > 0.0f ? Fixed(20.0 * std::log10(level), 1) : "-inf") +
                               " dBFS"
                         : "none (recording disabled)");
}

std::string PenLine(const platform::PenReading& pen) {
  return "Pen: pressure " + Fixed(pen.pressure, 2) + ", tilt " + Fixed(pen.TiltDeg(), 1) +
         " deg, at " + Fixed(pen.x_px, 0) + "," + Fixed(pen.y_px, 0) +
         (pen.origin == platform::PenOrigin::kTablet  ? " (tablet)"
          : pen.origin == platform::PenOrigin::kTouch ? " (touch)"
                                                      : " (mouse)");
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
      return low_vibration ? "Low vib on" : "Low vib off";
    case StaffButton::kVolumeDown:
      return "Volume -";
    case StaffButton::kVolumeUp:
      return "Volume +";
    case StaffButton::kVibrationDown:
      return "Vib -";
    case StaffButton::kVibrationUp:
      return "Vib +";
    case StaffButton::kCount:
      break;
  }
  return "";
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
  for (const auto& status : in.board->All()) {
    lines.push_back({status.device + ": " + platform::DeviceStateName(status.state) +
                         (status.backend.empty() ? "" : " (" + status.backend + ")") + " - " +
                         status.message,
                     status.state != platform::DeviceState::kOk});
  }
  lines.push_back({AudioLine(in)});
  lines.push_back({LatencyLine(in)});
  lines.push_back({DoseLine(engine)});
  lines.push_back({SwitchesLine(in)});
  lines.push_back({MicrophoneLine(engine)});
  lines.push_back({PenLine(in.pen)});
  const auto& counters = engine.session().counters();
  std::string strokes = "Strokes:";
  for (std::size_t t = 0; t < counters.strokes_per_texture.size(); ++t) {
    strokes +=
        " " + engine.textures()[t].key + " " + std::to_string(counters.strokes_per_texture[t]);
  }
  lines.push_back({strokes + ", voice " + std::to_string(counters.voice_strokes)});
  lines.push_back({"Recordings " + std::to_string(counters.recordings) + " (failed " +
                   std::to_string(counters.failed_recordings) + "), visits " +
                   std::to_string(counters.sessions) + ", cues " +
                   std::to_string(engine.cues_loaded()) +
                   (engine.staff_cues_loaded() > 0
                        ? " (" + std::to_string(engine.staff_cues_loaded()) + " staff-recorded)"
                        : "")});
  lines.push_back({in.config_line});
  const auto& staff = engine.staff_settings();
  lines.push_back({"Volume " + Fixed(staff.volume_db, 0) + " dB, vibration " +
                   Fixed(staff.vibration_db, 0) + " dB"});
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

#pragma once
// The kiosk configuration (kiosk_config.h) as each device's own settings: the microphone and its
// recorder, the audio output and its supervision, the token switches (GPIO lines or the MCP2221A
// adapter, with the same polarity and debounce for both) and the pen tablet. The live kiosk opens
// its devices with these, the virtual visits give their fake microphone the same recorder, and
// `--list-devices` says what the kiosk would use with the same keys.

#include "files/kiosk_config.h"
#include "platform/audio/audio_input.h"
#include "platform/audio/audio_output.h"
#include "platform/audio/voice_recorder.h"
#include "platform/discovery.h"
#include "platform/input/switch_factory.h"
#include "platform/pen/pen_source.h"

namespace sas::kiosk {

platform::AudioInputConfig AudioInputConfigFor(const KioskConfig& config);
platform::VoiceRecorderConfig RecorderConfigFor(const KioskConfig& config);
platform::AudioOutputConfig AudioOutputConfigFor(const KioskConfig& config);
platform::SwitchesConfig SwitchesConfigFor(const KioskConfig& config);
// The pen's coordinates are scaled to the screen it draws on (width x height pixels).
platform::PenConfig PenConfigFor(const KioskConfig& config, int screen_width_px,
                                 int screen_height_px);
// The keys that decide which devices the kiosk uses, for `--list-devices`' "use" lines.
platform::DeviceSelection DeviceSelectionFor(const KioskConfig& config);

}  // namespace sas::kiosk

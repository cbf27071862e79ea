#pragma once
// A voice-like test signal for machines with no microphone (the headless visit, the soak run): a
// glottal pulse train whose pitch glides +-25 % around `pitch_hz` (0.8 Hz), through three
// cascaded formant resonators (the vowels /a/, /i/, /u/ of Peterson & Barney 1952), one vowel
// per syllable (three syllables over `duration_s`) with a raised-cosine syllable envelope,
// normalised to -6 dBFS: neither too quiet nor clipped for the recorder.

#include <vector>

namespace sas::kiosk {

std::vector<float> SynthesiseVoice(double fs_hz, double duration_s, double pitch_hz = 120.0);

}  // namespace sas::kiosk

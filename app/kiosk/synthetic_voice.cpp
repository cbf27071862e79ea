// Synthesised speech-like test signal (see synthetic_voice.h).
#include "kiosk/synthetic_voice.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace sas::kiosk {
namespace {
constexpr double kPi = 3.14159265358979;
}  // namespace

std::vector<float> SynthesiseVoice(double fs_hz, double duration_s, double pitch_hz) {
  struct Vowel {
    double f[3];
    double b[3];
  };
  const Vowel vowels[3] = {{{730, 1090, 2440}, {90, 110, 170}},
                           {{270, 2290, 3010}, {60, 100, 170}},
                           {{300, 870, 2240}, {60, 90, 170}}};
  const auto n = static_cast<std::size_t>(duration_s * fs_hz);
  std::vector<float> out(n, 0.0f);
  double phase = 0.0;
  double state[3][2] = {};
  const double syllable_s = duration_s / 3.0;
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs_hz;
    const double f0 = pitch_hz * (1.0 + 0.25 * std::sin(2.0 * kPi * 0.8 * t));
    phase += f0 / fs_hz;
    double x = 0.0;
    if (phase >= 1.0) {
      phase -= 1.0;
      x = 1.0;  // one glottal pulse per period
    }
    const int syllable = std::min(2, static_cast<int>(t / syllable_s));
    const Vowel& v = vowels[syllable];
    for (int k = 0; k < 3; ++k) {
      const double r = std::exp(-kPi * v.b[k] / fs_hz);
      const double a1 = 2.0 * r * std::cos(2.0 * kPi * v.f[k] / fs_hz);
      const double a2 = -r * r;
      const double y = (1.0 - r) * x + a1 * state[k][0] + a2 * state[k][1];
      state[k][1] = state[k][0];
      state[k][0] = y;
      x = y;
    }
    const double u = std::fmod(t, syllable_s) / syllable_s;  // 0..1 in the syllable
    const double envelope = u < 0.85 ? std::pow(std::sin(kPi * u / 0.85), 2.0) : 0.0;
    out[i] = static_cast<float>(x * envelope);
    peak = std::max(peak, std::abs(x * envelope));
  }
  if (peak > 0.0) {
    for (auto& s : out)
      s = static_cast<float>(s * 0.5 / peak);  // -6 dBFS: neither quiet nor clipped
  }
  return out;
}

}  // namespace sas::kiosk

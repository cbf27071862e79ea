#pragma once
// True peak (ITU-R BS.1770-4 annex 2: 4× oversampled) of one channel of an interleaved buffer,
// measured by libebur128: an implementation independent of the safety stage under test.

#include <ebur128.h>

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace sas::test {

inline double TruePeak(const std::vector<float>& interleaved, int channels, int channel,
                       unsigned long rate = 48000) {
  std::vector<double> mono(interleaved.size() / static_cast<std::size_t>(channels));
  for (std::size_t i = 0; i < mono.size(); ++i) {
    mono[i] =
        interleaved[i * static_cast<std::size_t>(channels) + static_cast<std::size_t>(channel)];
  }
  ebur128_state* st = ebur128_init(1, rate, EBUR128_MODE_TRUE_PEAK);
  if (st == nullptr) throw std::runtime_error("ebur128_init failed");
  ebur128_add_frames_double(st, mono.data(), mono.size());
  double peak = 0.0;
  ebur128_true_peak(st, 0, &peak);
  ebur128_destroy(&st);
  return peak;
}

}  // namespace sas::test

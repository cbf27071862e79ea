// K-weighted loudness through libebur128, and RMS (see loudness.h). libebur128 designs the
// BS.1770 K-weighting for any sample rate (the standard tabulates it at 48 kHz only) and keeps the
// filtered signal of its momentary window (400 ms) in a ring buffer; ebur128_loudness_window()
// gives the ungated loudness of the last whole milliseconds fed, up to that length. A longer
// window is read as consecutive pieces of at most 400 ms, each when the feed reaches its end, and
// their energies added. Not a longer ring buffer: Debian 12's libebur128 (1.2.6) allocates 1000
// times the window asked of ebur128_set_max_window (375 MB a second at 48 kHz). The signal is fed
// once, every piece of every window read in the order they end: one filtering pass for any number
// of windows, overlapping or not.
#include "surface/loudness.h"

#include <ebur128.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

namespace sas::surface {
namespace {

struct Ebur128Deleter {
  void operator()(ebur128_state* state) const { ebur128_destroy(&state); }
};

constexpr double kLoudnessOffsetDb = -0.691;  // BS.1770: 1 kHz sine at 0 dBFS peak reads -3.01
constexpr std::size_t kPieceMs = 400;         // the momentary window, the ring buffer's length

double PowerDb(double mean_square) {
  return mean_square > 0.0 ? 10.0 * std::log10(mean_square) : kSilenceDb;
}

}  // namespace

double KWeightedLoudnessDb(std::span<const float> samples, double sample_rate_hz, std::size_t from,
                           std::size_t to, std::size_t stride) {
  const FrameWindow window{from, to};
  return KWeightedLoudnessDb(samples, sample_rate_hz, std::span(&window, 1), stride).front();
}

std::vector<double> KWeightedLoudnessDb(std::span<const float> samples, double sample_rate_hz,
                                        std::span<const FrameWindow> windows, std::size_t stride) {
  std::vector<double> loudness(windows.size(), kSilenceDb);
  const long rate_hz = std::lround(sample_rate_hz);
  if (stride == 0 || rate_hz <= 0) return loudness;
  const std::size_t frames = (samples.size() + stride - 1) / stride;
  const auto rate = static_cast<std::size_t>(rate_hz);

  // Each window as the library sees it: its length in whole milliseconds (rounded, but never
  // reaching back before the first frame, where the ring buffer holds zeros), read in pieces of
  // at most kPieceMs back to back from its end.
  struct Piece {
    std::size_t window = 0, end = 0;
    unsigned long ms = 0;
  };
  std::vector<Piece> pieces;
  std::vector<double> energy(windows.size(), 0.0);  // sum of squares over each window
  std::vector<std::size_t> length(windows.size(), 0);
  for (std::size_t w = 0; w < windows.size(); ++w) {
    const std::size_t to = std::min(windows[w].to, frames);
    if (windows[w].from >= to) continue;
    const std::size_t ms = std::min<std::size_t>(
        (2000 * (to - windows[w].from) + rate) / (2 * rate), 1000 * to / rate);
    length[w] = rate * ms / 1000;
    for (std::size_t done_ms = 0; done_ms < ms; done_ms += kPieceMs) {
      pieces.push_back({w, to - rate * done_ms / 1000,
                        static_cast<unsigned long>(std::min(kPieceMs, ms - done_ms))});
    }
  }
  if (pieces.empty()) return loudness;
  std::sort(pieces.begin(), pieces.end(),
            [](const Piece& a, const Piece& b) { return a.end < b.end; });

  std::unique_ptr<ebur128_state, Ebur128Deleter> meter(
      ebur128_init(1, static_cast<unsigned long>(rate_hz), EBUR128_MODE_M));
  if (!meter) throw std::runtime_error("libebur128: cannot measure at this sample rate");
  // The library reads whole frames of its own channel count: one channel, gathered in blocks.
  std::array<float, 4096> block{};
  std::size_t fed = 0;
  for (const Piece& piece : pieces) {
    while (fed < piece.end) {
      const std::size_t n = std::min(block.size(), piece.end - fed);
      for (std::size_t i = 0; i < n; ++i) block[i] = samples[(fed + i) * stride];
      ebur128_add_frames_float(meter.get(), block.data(), n);
      fed += n;
    }
    double lufs = 0.0;
    if (ebur128_loudness_window(meter.get(), piece.ms, &lufs) != EBUR128_SUCCESS) {
      throw std::runtime_error("libebur128: cannot read a loudness window");
    }
    if (std::isfinite(lufs)) {  // -inf: digital silence, no energy
      energy[piece.window] += std::pow(10.0, (lufs - kLoudnessOffsetDb) / 10.0) *
                              static_cast<double>(rate * piece.ms / 1000);
    }
  }
  for (std::size_t w = 0; w < windows.size(); ++w) {
    if (length[w] > 0 && energy[w] > 0.0) {
      loudness[w] = kLoudnessOffsetDb + PowerDb(energy[w] / static_cast<double>(length[w]));
    }
  }
  return loudness;
}

double RmsDb(std::span<const float> samples, std::size_t from, std::size_t to, std::size_t stride) {
  if (stride == 0) return kSilenceDb;
  const std::size_t frames = (samples.size() + stride - 1) / stride;
  to = std::min(to, frames);
  if (from >= to) return kSilenceDb;
  double sum = 0.0;
  for (std::size_t i = from; i < to; ++i) {
    const double x = samples[i * stride];
    sum += x * x;
  }
  return PowerDb(sum / static_cast<double>(to - from));
}

}  // namespace sas::surface

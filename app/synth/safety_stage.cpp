// The final safety stage (safety_stage.h).
#include "synth/safety_stage.h"

#include <algorithm>
#include <cmath>

namespace sas::synth {

void SafetyStage::Prepare(double sample_rate_hz, double release_s) {
  const double fs =
      sample_rate_hz > 0.0 && std::isfinite(sample_rate_hz) ? sample_rate_hz : 48000.0;
  const double release = release_s > 0.0 && std::isfinite(release_s) ? release_s : 0.05;
  release_step_ = 1.0 / (release * fs);
  // Point m + p/4 from x(m - h + 1 .. m + h), h = kTaps / 2: sinc at the distance, Hann window
  // over the span.
  constexpr int kHalf = kTaps / 2;
  for (int p = 1; p < 4; ++p) {
    for (int k = 0; k < kTaps; ++k) {
      const double t = (kHalf - 1) + p / 4.0 - k;  // distance from the point to tap k, in samples
      const double sinc = std::sin(M_PI * t) / (M_PI * t);
      const double window = 0.5 * (1.0 + std::cos(M_PI * t / kHalf));
      taps_[static_cast<std::size_t>(p)][static_cast<std::size_t>(k)] = sinc * window;
    }
  }
  taps_abs_sum_ = 1.0;
  for (int p = 1; p < 4; ++p) {
    double sum = 0.0;
    for (const double h : taps_[static_cast<std::size_t>(p)]) sum += std::fabs(h);
    taps_abs_sum_ = std::max(taps_abs_sum_, sum);
  }
  Reset();
}

void SafetyStage::SetCeilings(double speaker, double transducer) {
  const double margin = std::pow(10.0, -kMarginDb / 20.0);
  const auto sane = [&](double c) {
    return (std::isfinite(c) ? std::clamp(c, 1e-6, 1.0) : 1.0) * margin;
  };
  channel_[0].ceiling = sane(speaker);
  channel_[1].ceiling = sane(transducer);
  for (auto& ch : channel_) {
    ch.quiet_level = ch.ceiling / taps_abs_sum_;
    // Bounds stored under the old ceiling stay valid upper bounds; the slow path looks at them
    // again until the look-ahead has passed.
    ch.quiet_run = 0;
    ch.since_limited = 0;
  }
}

void SafetyStage::Reset() {
  for (auto& ch : channel_) {
    ch.x.fill(0.0);
    ch.bound.fill(0.0);
    ch.gain = 1.0;
    ch.quiet_run = 0;
    ch.since_limited = 0;
  }
  n_ = 0;
}

double SafetyStage::Step(Channel& ch, double in) {
  constexpr std::uint32_t kMask = kRing - 1;
  const auto at = [](std::uint32_t i) { return static_cast<std::size_t>(i & kMask); };
  const double x = std::isfinite(in) ? in : 0.0;
  ch.x[at(n_)] = x;
  ch.quiet_run = std::fabs(x) <= ch.quiet_level ? std::min(ch.quiet_run + 1, 1u << 30) : 0;
  // The bound for m = n - h, whose interpolation window x(m - h + 1 .. m + h) is now complete.
  constexpr int kHalf = kTaps / 2;
  const std::uint32_t m = n_ - kHalf;
  double bound = 0.0;
  if (ch.quiet_run >= static_cast<std::uint32_t>(kTaps)) {
    bound = ch.ceiling;  // ≥ quiet_level · S ≥ the true bound: needs no gain
  } else {
    bound = std::fabs(ch.x[at(m)]);
    for (int p = 1; p < 4; ++p) {
      const auto& taps = taps_[static_cast<std::size_t>(p)];
      double s = 0.0;
      for (int k = 0; k < kTaps; ++k) {
        s += taps[static_cast<std::size_t>(k)] *
             ch.x[at(m - (kHalf - 1) + static_cast<std::uint32_t>(k))];
      }
      bound = std::max(bound, std::fabs(s));
    }
  }
  ch.bound[at(m)] = bound;
  ch.since_limited = bound > ch.ceiling ? 0 : std::min(ch.since_limited + 1, 1u << 30);
  // The sample going out, o = m - kLookahead: needs are known up to o + kLookahead.
  const std::uint32_t o = m - kLookahead;
  const double c = ch.ceiling;
  const auto need = [&](std::uint32_t i) {
    const double b = ch.bound[at(i)];
    return b > c ? c / b : 1.0;
  };
  double g = std::min(ch.gain + release_step_, 1.0);
  constexpr int kReach = kHalf + kHold;
  if (ch.since_limited > static_cast<std::uint32_t>(kLookahead + kReach)) {
    // No bound over the ceiling from o - kReach to o + kLookahead: only the release moves.
    ch.gain = g;
    return g * ch.x[at(o)];
  }
  // Hard part: every interpolated point this sample takes part in (m' in o - h .. o + h - 1),
  // widened by kHold on each side so that the gain is flat across an interpolation window (a gain
  // changing within the window makes inter-sample peaks of its own).
  for (int j = -kReach; j < kReach; ++j) g = std::min(g, need(o + static_cast<std::uint32_t>(j)));
  // Ramp part: reductions further ahead start fading in now.
  for (int j = kReach; j <= kLookahead; ++j) {
    const double r = need(o + static_cast<std::uint32_t>(j));
    if (r < 1.0) {
      g = std::min(g,
                   r + (1.0 - r) * (j - kReach + 1) / static_cast<double>(kLookahead - kReach + 2));
    }
  }
  g = std::min(g, 1.0);
  ch.gain = g;
  return g * ch.x[at(o)];
}

void SafetyStage::Process(float* frame) {
  const double speaker = Step(channel_[0], static_cast<double>(frame[0]));
  const double transducer = Step(channel_[1], static_cast<double>(frame[1]));
  ++n_;
  frame[0] = static_cast<float>(speaker);
  frame[1] = static_cast<float>(transducer);
}

}  // namespace sas::synth

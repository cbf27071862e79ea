// Micro-roughness (RoughnessParams): the friction noise and the felt roughness are random
// profiles of the distance travelled, so their spectrum in time scales with the stroke's speed.
// Checked on a flat surface (no picture relief), against the white noise of a smooth material.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "support/fft.h"
#include "synth/scene.h"
#include "synth_test_support.h"

using namespace sas::synth;
using sas::synth::test::OwnedField;

namespace {

constexpr double kFs = 48000.0;

// Power-weighted mean frequency of channel 1 over frames [begin, begin + 2^15).
double Centroid(const std::vector<float>& stereo, std::size_t begin) {
  const std::size_t n = 1u << 15;
  std::vector<double> re(n), im(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(i) / n);
    re[i] = w * stereo[2 * (begin + i)];
  }
  sas::test::FftInPlace(re, im);
  double weighted = 0.0, total = 0.0;
  for (std::size_t k = 1; k < n / 2; ++k) {
    const double p = re[k] * re[k] + im[k] * im[k];
    weighted += p * static_cast<double>(k) * kFs / n;
    total += p;
  }
  return weighted / total;
}

// A steady stroke on flat ground at `speed_mps`, pen resting `settle_s` first (the landing's ring
// dies away); the centroid of the sustained part after it.
double StrokeCentroid(const MaterialParams& material, double speed_mps, double* rms,
                      ProbeStyle style = ProbeStyle::kScrape, double settle_s = 0.2) {
  OwnedField field(4000, 8, 0.153e-3, std::vector<float>(4000 * 8, 0.0f));
  Scene scene;
  scene.Init(kFs);
  scene.Prepare(material, OutputParams{}, field.view);
  ProbeCommand down;
  down.tip_down = true;
  down.x_m = 0.01;
  down.y_m = 0.0006;
  down.normal_force_n = 0.8;
  down.width_mm = 0.3;
  down.landing_speed_mps = 0.005;
  down.style = style;
  ProbeCommand move = down;
  move.velocity_mps = speed_mps;
  const long settle = static_cast<long>(settle_s * kFs);
  const long total = settle + static_cast<long>(0.05 * kFs) + (1L << 15);
  const auto out = sas::synth::test::RenderTimed(scene, {{0, down}, {settle, move}}, total, 256);
  const auto begin = static_cast<std::size_t>(settle + static_cast<long>(0.05 * kFs));
  double sum = 0.0;
  for (std::size_t i = begin; i < begin + (1u << 15); ++i) sum += out[2 * i] * out[2 * i];
  *rms = std::sqrt(sum / (1u << 15));
  return Centroid(out, begin);
}

}  // namespace

TEST_CASE("roughness: a rough material's friction noise brightens with the stroke's speed, a "
          "smooth material's white noise does not",
          "[dsp][friction]") {
  MaterialParams rough = sas::synth::test::WoodLikeBoard();
  rough.friction.noise_coefficient = 2.0;
  rough.roughness.enabled = true;
  rough.roughness.rms_m = 0.0;        // the friction noise alone
  rough.roughness.length_m = 100e-6;  // 30 mm/s: corner at 48 Hz; 300 mm/s: 480 Hz
  MaterialParams smooth = rough;
  smooth.roughness.enabled = false;

  double rms_slow = 0.0, rms_fast = 0.0;
  const double rough_slow = StrokeCentroid(rough, 0.03, &rms_slow);
  const double rough_fast = StrokeCentroid(rough, 0.3, &rms_fast);
  INFO("rough: " << rough_slow << " Hz -> " << rough_fast << " Hz, rms " << rms_slow << " -> "
                 << rms_fast);
  CHECK(rough_fast > 1.3 * rough_slow);
  CHECK(rms_fast > 2.0 * rms_slow);  // and louder (+6 dB)

  double unused = 0.0;
  const double smooth_slow = StrokeCentroid(smooth, 0.03, &unused);
  const double smooth_fast = StrokeCentroid(smooth, 0.3, &unused);
  INFO("smooth: " << smooth_slow << " Hz -> " << smooth_fast << " Hz");
  CHECK(smooth_fast < 1.3 * smooth_slow);
}

TEST_CASE("roughness: the height the probe feels adds sound on flat ground, through a point and "
          "through a rolling ball",
          "[dsp][friction]") {
  MaterialParams m = sas::synth::test::WoodLikeBoard();
  m.friction.enabled = false;  // the normal direction alone
  m.roughness.enabled = true;
  m.roughness.length_m = 50e-6;
  m.roughness.rms_m = 0.0;
  double flat = 0.0;
  StrokeCentroid(m, 0.2, &flat, ProbeStyle::kScrape, 1.5);
  m.roughness.rms_m = 4e-6;
  double point = 0.0, ball = 0.0;
  StrokeCentroid(m, 0.2, &point, ProbeStyle::kScrape, 1.5);
  StrokeCentroid(m, 0.2, &ball, ProbeStyle::kRoll, 1.5);
  INFO("rms without height " << flat << ", with 4 um: point " << point << ", ball " << ball);
  CHECK(point > 5.0 * flat);
  CHECK(ball > 5.0 * flat);
}

// The modes ring at the set frequency and decay at the set rate, up to
// 0.45 fs, at 44.1, 48 and 96 kHz. The rendered signal is fitted by the exact two-term recursion of
// a sampled damped sinusoid (least squares), independent of how the resonator computes it.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "synth/modal_resonator.h"
#include "synth/scene.h"
#include "synth_test_support.h"

using namespace sas::synth;

TEST_CASE(
    "a struck mode rings at the set frequency within 0.01 cent and decays within 0.5 % "
    "up to 0.45 fs at 44.1, 48 and 96 kHz",
    "[dsp]") {
  for (const double fs : {44100.0, 48000.0, 96000.0}) {
    for (const double ratio : {20.0 / 48000.0, 0.001, 0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.449}) {
      for (const double decay_s : {0.005, 0.1, 2.0}) {
        const double f = ratio * fs;
        ResonatorParams params;
        params.mode_count = 1;
        params.modes[0] = ModeParams{f, decay_s, 0.02, 1.0};
        ModalState modes;
        modes.Prepare(params, fs, 4);
        REQUIRE(modes.count == 1);
        // Strike: a force impulse through the sub-step map, then free ringing.
        AdvanceModes(modes, modes.sub, 50.0);
        const auto n = static_cast<std::size_t>(std::min(4.0 * decay_s * fs, 20000.0));
        std::vector<double> out(n);
        for (auto& y : out) {
          AdvanceModes(modes, modes.full, 0.0);
          y = modes.PickupVelocity();
        }
        const auto fit = test::FitDampedSine(out, 0, out.size(), fs);
        INFO("fs " << fs << " f " << f << " decay " << decay_s);
        CHECK(std::fabs(test::Cents(fit.frequency_hz, f)) < 0.01);
        CHECK(fit.decay_s == Approx(decay_s).epsilon(0.005));
      }
    }
  }
}

TEST_CASE("modes at or above 0.45 fs and modes with negligible gain are not computed", "[dsp]") {
  ResonatorParams params;
  params.mode_count = 4;
  params.modes[0] = ModeParams{1000.0, 0.1, 0.01, 1.0};
  params.modes[1] = ModeParams{0.45 * 48000.0, 0.1, 0.01, 1.0};
  params.modes[2] = ModeParams{30000.0, 0.1, 0.01, 1.0};
  params.modes[3] = ModeParams{2000.0, 0.1, 0.01, 0.0};
  ModalState modes;
  modes.Prepare(params, 48000.0, 1);
  CHECK(modes.count == 1);
  modes.Prepare(params, 96000.0, 1);
  CHECK(modes.count == 3);
}

TEST_CASE(
    "a mode struck through the scene's contact rings at its frequency in the rendered "
    "sound channel",
    "[dsp][render]") {
  for (const double fs : {44100.0, 48000.0, 96000.0}) {
    for (const double f : {110.0, 3000.0, 0.449 * fs}) {
      MaterialParams material;
      material.friction.enabled = false;
      material.impact.stiffness = 1e11;  // a hard, short contact excites even 0.449 fs
      material.probe.mass_kg = 0.001;
      material.impact.dissipation_s_per_m = 0.3;
      material.resonator.mode_count = 1;
      material.resonator.modes[0] = ModeParams{f, 0.2, 0.05, 1.0};
      OutputParams output;
      output.sound_gain = 0.5;  // keep the limiter in its linear part
      Scene scene;
      scene.Init(fs);
      scene.Prepare(material, output, HeightFieldView{});
      ProbeCommand burst;
      burst.burst_impulse_n_s = 1e-4;
      const int frames = static_cast<int>(0.3 * fs);
      std::vector<float> out(static_cast<std::size_t>(2 * frames));
      scene.Process(&burst, 1, out.data(), frames);
      REQUIRE(!scene.probe_state().active);  // the probe bounced off and was parked
      std::vector<float> sound(static_cast<std::size_t>(frames));
      for (int i = 0; i < frames; ++i)
        sound[static_cast<std::size_t>(i)] = out[2 * static_cast<std::size_t>(i)];
      float peak = 0.0f;
      for (float s : sound) peak = std::max(peak, std::fabs(s));
      REQUIRE(peak > 1e-5f);
      REQUIRE(peak < 0.5f);
      // Fit well after the contact (a few ms) on the float output.
      const auto fit =
          test::FitDampedSine(sound, static_cast<std::size_t>(0.01 * fs), sound.size(), fs);
      INFO("fs " << fs << " f " << f);
      CHECK(std::fabs(test::Cents(fit.frequency_hz, f)) < 0.01);
      CHECK(fit.decay_s == Approx(0.2).epsilon(0.005));
    }
  }
}

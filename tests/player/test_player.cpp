// The player's two faces through its message API alone: while the audio device is stopped nothing
// but a switch is queued (the audio side stays the queue's only consumer), and what waited is
// taken, in order, once blocks are rendered again.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "player/player.h"
#include "synth/synth_test_support.h"

using sas::player::Player;
using sas::player::PlayerClip;
using sas::player::PlayerSetup;
using sas::synth::ProbeCommand;
using sas::synth::Scene;
using sas::synth::test::OwnedField;
using sas::synth::test::WoodLikeBoard;

namespace {

constexpr int kFrames = 128;

OwnedField& Field() {
  static OwnedField field(400, 1, 0.153e-3, std::vector<float>(400, 20e-6f));
  return field;
}

void PrepareWood(Scene& scene) {
  scene.Prepare(WoodLikeBoard(), {}, Field().view);
}

ProbeCommand Stroke(double x_m) {
  ProbeCommand command;
  command.tip_down = true;
  command.x_m = x_m;
  command.velocity_mps = 0.1;
  command.normal_force_n = 0.5;
  command.penetration_m = 20e-6;
  return command;
}

std::vector<float> RenderBlock(Player& player) {
  std::vector<float> out(2 * kFrames);
  player.audio().Render(out.data(), kFrames, 2);
  return out;
}

}  // namespace

TEST_CASE(
    "player: with the device stopped strokes are not queued but a switch is, and running again the "
    "audio side takes the switch and then the pen as it is now",
    "[dsp]") {
  Player player(PlayerSetup{}, {}, PrepareWood);
  auto& control = player.control();
  CHECK(control.SwitchTaken());  // the first scene plays from the first block
  CHECK(control.stats().switches == 1);

  for (int i = 0; i < 50; ++i) control.Probe(i * 1'000'000, Stroke(0.01 + 1e-4 * i));
  const int slot = control.FreeSlot();
  REQUIRE(slot > 0);
  PrepareWood(control.scene(slot));
  REQUIRE(control.Switch(50'000'000, slot));
  CHECK_FALSE(control.SwitchTaken());
  CHECK(control.SlotInUse(slot));
  CHECK(control.FreeSlot() != slot);

  control.SetDeviceRunning(true, 60'000'000);
  RenderBlock(player);
  CHECK(control.SwitchTaken());
  CHECK(control.current_slot() == slot);
  const auto stats = control.stats();
  CHECK(stats.switches == 2);
  CHECK(stats.commands == 1);  // the held pen state, not the fifty strokes made meanwhile
  CHECK(stats.dropped_commands == 0);
}

TEST_CASE("player: a cue cut off by a device outage does not play on when the device is back",
          "[dsp]") {
  std::vector<PlayerClip> clips(1);
  clips[0].samples.assign(48000, 0.1f);
  Player player(PlayerSetup{}, std::move(clips), PrepareWood);
  auto& control = player.control();
  control.SetDeviceRunning(true, 0);
  control.Play(0, 0);
  RenderBlock(player);  // the cue starts one buffer after it was asked for
  const auto playing = RenderBlock(player);
  CHECK(control.clip_playing());
  CHECK(std::fabs(playing[2 * (kFrames - 1)]) > 0.05f);

  control.SetDeviceRunning(false, 0);
  control.Play(0, 0);  // not queued: nothing could hear it
  control.SetDeviceRunning(true, 0);
  for (int b = 0; b < 4; ++b) RenderBlock(player);  // past the safety stage's delay line
  CHECK_FALSE(control.clip_playing());
  const auto after = RenderBlock(player);
  for (const float sample : after) CHECK(sample == 0.0f);
}

namespace {

// A sine on the transducer channel as a clip: `seconds` at `hz`, amplitude `level`.
std::vector<PlayerClip> TransducerSine(double hz, double level, double seconds) {
  std::vector<PlayerClip> clips(1);
  clips[0].channel = 1;
  clips[0].samples.resize(static_cast<std::size_t>(seconds * 48000.0));
  for (std::size_t n = 0; n < clips[0].samples.size(); ++n) {
    clips[0].samples[n] =
        static_cast<float>(level * std::sin(2.0 * M_PI * hz * static_cast<double>(n) / 48000.0));
  }
  return clips;
}

// Plays clip 0 and returns the largest |ch 2| sample over `blocks` blocks from the 60th on (0.16 s:
// past the start and 20 time constants of the compensation's settling), and the largest of all.
struct Peaks {
  double steady = 0.0;
  double all = 0.0;
};
Peaks PlayOnTransducer(const PlayerSetup& setup, std::vector<PlayerClip> clips, int blocks) {
  Player player(setup, std::move(clips), PrepareWood);
  player.control().SetDeviceRunning(true, 0);
  player.control().Play(0, 0);
  Peaks peaks;
  for (int b = 0; b < blocks; ++b) {
    const auto out = RenderBlock(player);
    for (std::size_t i = 1; i < out.size(); i += 2) {
      const double v = std::fabs(out[i]);
      peaks.all = std::max(peaks.all, v);
      if (b >= 60) peaks.steady = std::max(peaks.steady, v);
    }
  }
  return peaks;
}

}  // namespace

TEST_CASE(
    "player: a transducer profile compensates ch 2 of the mix (an LRA's resonance drawn down by "
    "its Q), and none leaves it as it was",
    "[dsp]") {
  PlayerSetup flat;
  PlayerSetup lra;
  lra.transducer_resonance_hz = 175.0;
  lra.transducer_q = 10.0;
  const auto clip = [] { return TransducerSine(175.0, 0.5, 0.5); };
  const Peaks as_is = PlayOnTransducer(flat, clip(), 150);
  const Peaks compensated = PlayOnTransducer(lra, clip(), 150);
  CHECK(as_is.steady == Approx(0.5).epsilon(0.01));  // a clip's samples pass unchanged
  // At its resonance the actuator gives Q times the acceleration: the drive is Q times smaller
  // (|C| = (w0^2 / Q) / |wL^2 - w0^2 + j w0 wL / QL| = 0.09996 at 175 Hz).
  const double ratio_db = 20.0 * std::log10(compensated.steady / as_is.steady);
  CHECK(ratio_db == Approx(-20.0).margin(0.3));
}

TEST_CASE(
    "player: the compensation comes before the safety stage: a loud 40 Hz clip boosted by an LRA "
    "profile still never exceeds the transducer's ceiling",
    "[dsp][safety]") {
  PlayerSetup setup;
  setup.transducer_resonance_hz = 175.0;  // +24 dB at 40 Hz
  setup.transducer_q = 10.0;
  setup.transducer_ceiling = 0.5;
  const Peaks peaks = PlayOnTransducer(setup, TransducerSine(40.0, 0.9, 0.5), 150);
  CHECK(peaks.all <= 0.5);
  CHECK(peaks.steady > 0.4);  // the clip did play, limited to the ceiling
  // Low vibration lowers that ceiling, and the boosted drive stays under it too.
  setup.low_vibration = true;
  setup.low_vibration_factor = 0.25;
  const Peaks low = PlayOnTransducer(setup, TransducerSine(40.0, 0.9, 0.5), 150);
  CHECK(low.all <= 0.125);
  CHECK(low.steady > 0.1);
}

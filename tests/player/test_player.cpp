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

// The Session state machine: each visitor-facing rule, driven with explicit times.
#include <algorithm>
#include <catch2/catch.hpp>

#include "kiosk/session.h"

using sas::kiosk::Cue;
using sas::kiosk::RecordingOutcome;
using sas::kiosk::Session;
using sas::kiosk::SessionAction;
using sas::kiosk::SessionConfig;
using sas::kiosk::SessionMode;
using Kind = SessionAction::Kind;

namespace {

SessionConfig Config() {
  SessionConfig config;
  config.texture_count = 4;
  config.default_texture = 2;
  config.idle_timeout_s = 60.0;
  config.countdown_s = 3.0;
  config.record_max_s = 5.0;
  config.long_hold_s = 1.2;
  return config;
}

int Count(const std::vector<SessionAction>& actions, Kind kind) {
  return static_cast<int>(std::count_if(actions.begin(), actions.end(),
                                        [kind](const auto& a) { return a.kind == kind; }));
}

const SessionAction* Find(const std::vector<SessionAction>& actions, Kind kind) {
  for (const auto& action : actions) {
    if (action.kind == kind) return &action;
  }
  return nullptr;
}

}  // namespace

TEST_CASE("a placed token cross-fades to its texture and speaks its name", "[kiosk]") {
  Session session(Config());
  REQUIRE(session.mode() == SessionMode::kAttract);
  session.OnTokenSelection(1.0, 3);
  const auto actions = session.TakeActions();
  REQUIRE(Count(actions, Kind::kLeaveAttract) == 1);
  const auto* show = Find(actions, Kind::kShowSurface);
  REQUIRE(show != nullptr);
  CHECK(show->surface.texture == 3);
  const auto* speak = Find(actions, Kind::kSpeak);
  REQUIRE(speak != nullptr);
  CHECK(speak->cue == Cue::kTextureName);
  CHECK(speak->surface.texture == 3);
  CHECK(session.surface().texture == 3);
  // Lifting the token returns to the default texture.
  session.OnTokenSelection(2.0, -1);
  CHECK(session.surface().texture == 2);
}

TEST_CASE("choosing the texture already shown neither cross-fades nor repeats its name",
          "[kiosk]") {
  Session session(Config());
  session.OnTokenSelection(1.0, 1);
  session.TakeActions();
  session.OnTokenSelection(1.5, 1);
  CHECK(session.TakeActions().empty());
}

TEST_CASE("record press counts down, records, and a good take becomes the surface", "[kiosk]") {
  Session session(Config());
  session.OnPen(0.5, false);
  session.OnRecordButton(1.0, true);
  session.OnRecordButton(1.1, false);
  CHECK(session.mode() == SessionMode::kCountdown);
  CHECK(session.SecondsLeft(2.0) == Approx(2.0));
  session.Tick(3.9);
  CHECK(Count(session.TakeActions(), Kind::kStartRecording) == 0);
  session.Tick(4.0);
  CHECK(session.mode() == SessionMode::kRecording);
  CHECK(Count(session.TakeActions(), Kind::kStartRecording) == 1);
  session.Tick(9.0);  // 5 s later the take ends by itself
  CHECK(Count(session.TakeActions(), Kind::kStopRecording) == 1);
  session.OnRecordingFinished(9.1, RecordingOutcome::kOk);
  const auto actions = session.TakeActions();
  const auto* show = Find(actions, Kind::kShowSurface);
  REQUIRE(show != nullptr);
  CHECK(show->surface.voice);
  CHECK(session.has_voice());
  CHECK(session.counters().recordings == 1);
}

TEST_CASE("a silent or clipped take keeps the previous surface and says why", "[kiosk]") {
  for (const auto outcome : {RecordingOutcome::kSilent, RecordingOutcome::kClipped}) {
    Session session(Config());
    session.OnTokenSelection(0.0, 0);
    session.OnRecordButton(1.0, true);
    session.OnRecordButton(1.1, false);
    session.Tick(4.0);
    session.Tick(9.0);
    session.TakeActions();
    session.OnRecordingFinished(9.1, outcome);
    const auto actions = session.TakeActions();
    CHECK(Find(actions, Kind::kShowSurface) == nullptr);
    const auto* speak = Find(actions, Kind::kSpeak);
    REQUIRE(speak != nullptr);
    CHECK(speak->cue == (outcome == RecordingOutcome::kSilent ? Cue::kRecordingTooQuiet
                                                              : Cue::kRecordingTooLoud));
    CHECK_FALSE(session.surface().voice);
    CHECK(session.surface().texture == 0);
    CHECK(session.counters().failed_recordings == 1);
  }
}

TEST_CASE("a second press during the countdown or a long hold speaks the description instead",
          "[kiosk]") {
  SECTION("second press") {
    Session session(Config());
    session.OnTokenSelection(0.0, 1);
    session.OnRecordButton(1.0, true);
    session.OnRecordButton(1.2, false);
    session.OnRecordButton(1.5, true);
    const auto actions = session.TakeActions();
    const auto speaks = std::count_if(actions.begin(), actions.end(), [](const auto& a) {
      return a.kind == Kind::kSpeak && a.cue == Cue::kTextureDescription && a.surface.texture == 1;
    });
    CHECK(speaks == 1);
    CHECK(session.mode() == SessionMode::kExploring);
    session.Tick(10.0);
    CHECK(Count(session.TakeActions(), Kind::kStartRecording) == 0);
  }
  SECTION("long hold") {
    Session session(Config());
    session.OnTokenSelection(0.0, 1);
    session.OnRecordButton(1.0, true);
    session.Tick(2.0);
    CHECK(session.mode() == SessionMode::kCountdown);
    session.TakeActions();
    session.Tick(2.3);
    const auto actions = session.TakeActions();
    REQUIRE(Find(actions, Kind::kSpeak) != nullptr);
    CHECK(Find(actions, Kind::kSpeak)->cue == Cue::kTextureDescription);
    CHECK(session.mode() == SessionMode::kExploring);
    session.Tick(2.5);  // still held: spoken once only
    CHECK(session.TakeActions().empty());
  }
}

TEST_CASE("after the idle timeout the voice is wiped, bubbles reset, the token's texture, attract",
          "[kiosk]") {
  Session session(Config());
  session.OnTokenSelection(0.0, 3);
  session.OnRecordButton(1.0, true);
  session.OnRecordButton(1.1, false);
  session.Tick(4.0);
  session.Tick(9.0);
  session.OnRecordingFinished(9.0, RecordingOutcome::kOk);
  session.OnPen(10.0, true);
  session.OnPen(12.0, false);
  session.TakeActions();
  session.Tick(71.9);
  CHECK(session.TakeActions().empty());
  session.Tick(72.0);
  const auto actions = session.TakeActions();
  CHECK(Count(actions, Kind::kWipeVoice) == 1);
  CHECK(Count(actions, Kind::kResetTextures) == 1);
  CHECK(Count(actions, Kind::kEnterAttract) == 1);
  CHECK_FALSE(session.has_voice());
  CHECK(session.mode() == SessionMode::kAttract);
  CHECK(session.surface() == sas::kiosk::SurfaceChoice{false, 3});  // the token is still there
  // Any touch leaves the attract screen at once and starts a new visit.
  session.OnPen(80.0, true);
  CHECK(Count(session.TakeActions(), Kind::kLeaveAttract) == 1);
  CHECK(session.counters().sessions == 2);
}

TEST_CASE("the idle reset waits while the pen is down, a take is running or staff are at work",
          "[kiosk]") {
  Session session(Config());
  session.OnPen(0.0, true);
  session.Tick(100.0);
  CHECK(session.mode() == SessionMode::kExploring);
  session.OnPen(100.0, false);
  session.OnStaffChord(101.0);
  session.Tick(300.0);
  CHECK(session.mode() == SessionMode::kExploring);
  session.OnStaffChord(300.0);
  session.Tick(360.0);
  CHECK(session.mode() == SessionMode::kAttract);
}

TEST_CASE("strokes are counted per texture and for the voice surface", "[kiosk]") {
  Session session(Config());
  session.OnTokenSelection(0.0, 1);
  for (int i = 0; i < 3; ++i) {
    session.OnPen(1.0 + i, true);
    session.OnPen(1.5 + i, false);
  }
  session.OnPen(5.0, false);  // a second "up" is not a stroke
  session.OnTokenSelection(6.0, 0);
  session.OnPen(7.0, true);
  CHECK(session.counters().strokes_per_texture == std::vector<std::uint64_t>{1, 3, 0, 0});
}

TEST_CASE("after an idle reset the texture follows the token still on a switch", "[kiosk]") {
  Session session(Config());
  session.OnTokenSelection(0.0, 1);  // broken glass, and the visitor walks away leaving it
  session.OnPen(1.0, true);
  session.OnPen(2.0, false);
  session.TakeActions();
  session.Tick(62.0);
  const auto actions = session.TakeActions();
  REQUIRE(session.mode() == SessionMode::kAttract);
  CHECK(session.surface() == sas::kiosk::SurfaceChoice{false, 1});
  CHECK(Find(actions, Kind::kSpeak) == nullptr);  // nobody there to hear the name
  // Lifted during the attract screen: the default texture again.
  session.OnTokenSelection(70.0, -1);
  CHECK(session.surface() == sas::kiosk::SurfaceChoice{false, 2});
}

TEST_CASE("a voice surface left by a visitor goes back to the token's texture at the idle reset",
          "[kiosk]") {
  Session session(Config());
  session.OnTokenSelection(0.0, 3);
  session.OnRecordButton(1.0, true);
  session.OnRecordButton(1.1, false);
  session.Tick(4.0);
  session.Tick(9.0);
  session.OnRecordingFinished(9.0, RecordingOutcome::kOk);
  REQUIRE(session.surface().voice);
  session.Tick(70.0);
  CHECK(session.surface() == sas::kiosk::SurfaceChoice{false, 3});
}

TEST_CASE("the staff panel closes itself after its timeout and the idle reset follows", "[kiosk]") {
  SessionConfig config = Config();
  config.staff_panel_timeout_s = 120.0;
  Session session(config);
  session.OnPen(0.0, true);
  session.OnPen(1.0, false);
  session.OnStaffChord(10.0);
  REQUIRE(session.staff_panel_open());
  session.TakeActions();
  session.OnStaffActivity(100.0);  // a button on the panel: the timeout restarts
  session.Tick(219.0);
  CHECK(session.staff_panel_open());
  CHECK(session.mode() == SessionMode::kExploring);  // staff at work: no idle reset
  session.Tick(220.0);
  CHECK_FALSE(session.staff_panel_open());
  const auto actions = session.TakeActions();
  const auto* closed = Find(actions, Kind::kStaffPanel);
  REQUIRE(closed != nullptr);
  CHECK_FALSE(closed->open);
  // The idle timer starts when the panel closed, not when staff opened it.
  session.Tick(279.0);
  CHECK(session.mode() == SessionMode::kExploring);
  session.Tick(280.0);
  CHECK(session.mode() == SessionMode::kAttract);
  // The chord opens it again as before.
  session.OnStaffChord(300.0);
  CHECK(session.staff_panel_open());
}

TEST_CASE("a visit is counted at its first pen contact only", "[kiosk]") {
  Session session(Config());
  // A mouse hover over the attract screen is nobody: it neither leaves attract nor counts.
  session.OnPen(1.0, false);
  session.OnPen(1.5, false);
  CHECK(session.mode() == SessionMode::kAttract);
  CHECK(session.TakeActions().empty());
  // A token put on (or found on a switch at start) leaves attract but is not yet a visit.
  session.OnTokenSelection(2.0, 0);
  CHECK(session.mode() == SessionMode::kExploring);
  CHECK(session.counters().sessions == 0);
  session.OnPen(3.0, false);  // hovering while exploring
  CHECK(session.counters().sessions == 0);
  session.OnPen(4.0, true);  // the pen touches: one visit
  CHECK(session.counters().sessions == 1);
  session.OnPen(5.0, false);
  session.OnPen(6.0, true);  // more strokes in the same visit
  session.OnPen(7.0, false);
  CHECK(session.counters().sessions == 1);
  CHECK(session.counters().strokes_per_texture[0] == 2);
  // Idle reset, then only a record press and a token: still no second visit.
  session.Tick(67.0);
  REQUIRE(session.mode() == SessionMode::kAttract);
  session.OnRecordButton(70.0, true);
  session.OnRecordButton(70.1, false);
  session.OnRecordButton(70.2, true);  // second press: the description instead
  session.OnRecordButton(70.3, false);
  CHECK(session.counters().sessions == 1);
  session.OnPen(71.0, true);
  CHECK(session.counters().sessions == 2);
}

TEST_CASE(
    "the attract cycle gives each language its slot: shown and invited in turn, paused by "
    "the staff panel, and started over with the configured language at the idle reset",
    "[kiosk]") {
  SessionConfig config = Config();
  config.attract_slots_s = {10.0, 12.0, 11.0};
  CHECK(sas::kiosk::AttractCycleS(config) == Approx(33.0));
  Session session(config);
  std::vector<std::pair<double, int>> slots;  // when each slot began, and which
  const auto run = [&](double from_s, double to_s) {
    for (double t = from_s; t < to_s; t += 0.01) {
      session.Tick(t);
      const auto actions = session.TakeActions();
      for (std::size_t i = 0; i < actions.size(); ++i) {
        if (actions[i].kind != Kind::kAttractLanguage) continue;
        slots.emplace_back(t, actions[i].count);
        // Its invitation follows at once, in the slot's language.
        REQUIRE(i + 1 < actions.size());
        CHECK(actions[i + 1].kind == Kind::kSpeak);
        CHECK(actions[i + 1].cue == Cue::kInvitation);
      }
    }
  };
  run(0.0, 40.0);
  REQUIRE(slots.size() == 4);
  CHECK(slots[0].second == 0);
  CHECK(slots[1].second == 1);
  CHECK(slots[2].second == 2);
  CHECK(slots[3].second == 0);  // and round again
  CHECK(slots[1].first - slots[0].first == Approx(10.0).margin(0.02));
  CHECK(slots[2].first - slots[1].first == Approx(12.0).margin(0.02));
  CHECK(slots[3].first - slots[2].first == Approx(11.0).margin(0.02));
  // The staff panel over the attract screen holds the cycle.
  session.OnStaffChord(40.0);
  session.TakeActions();
  slots.clear();
  run(40.0, 70.0);
  CHECK(slots.empty());
  session.OnStaffChord(70.0);
  session.TakeActions();
  run(70.0, 70.1);
  REQUIRE(slots.size() == 1);
  CHECK(slots[0].second == 1);  // where it was
  // A visit stops it; the idle reset starts it over with slot 0 at once.
  session.OnPen(71.0, true);
  session.OnPen(71.1, false);
  session.TakeActions();
  slots.clear();
  run(71.1, 71.1 + config.idle_timeout_s + 0.05);
  REQUIRE(slots.size() == 1);
  CHECK(slots[0].second == 0);
  CHECK(slots[0].first == Approx(71.1 + config.idle_timeout_s).margin(0.02));
  // Without slots nothing is spoken on the attract screen.
  Session quiet(Config());
  for (double t = 0.0; t < 100.0; t += 0.5) quiet.Tick(t);
  CHECK(Count(quiet.TakeActions(), Kind::kSpeak) == 0);
}

TEST_CASE(
    "a visit's texture is named when it starts, by a touch or by a token choosing the "
    "texture already shown",
    "[kiosk]") {
  {
    Session session(Config());
    session.OnPen(1.0, true);
    const auto actions = session.TakeActions();
    const auto* speak = Find(actions, Kind::kSpeak);
    REQUIRE(speak != nullptr);
    CHECK(speak->cue == Cue::kTextureName);
    CHECK(speak->surface.texture == 2);
    session.OnPen(1.5, false);
    session.OnPen(2.0, true);  // the next stroke of the same visit: no name again
    CHECK(Count(session.TakeActions(), Kind::kSpeak) == 0);
  }
  {
    Session session(Config());
    session.OnTokenSelection(1.0, 2);  // the default texture, already shown
    const auto actions = session.TakeActions();
    CHECK(Count(actions, Kind::kShowSurface) == 0);
    const auto* speak = Find(actions, Kind::kSpeak);
    REQUIRE(speak != nullptr);
    CHECK(speak->cue == Cue::kTextureName);
    session.OnPen(2.0, true);  // named already
    CHECK(Count(session.TakeActions(), Kind::kSpeak) == 0);
  }
}

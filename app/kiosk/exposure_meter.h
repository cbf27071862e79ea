#pragma once
// The speaker's long-term exposure for staff: its equivalent continuous level (Leq, the mean
// square of the samples sent to the speaker, in dB re full scale) over the last visit and over
// the last hour. In a loud room gains are exaggerated; what matters for the staff's and the
// visitors' ears is the dose, not the peaks (the safety stage caps those). Staff turn it into
// dB SPL at the visitor's ear once with a phone meter (README, staff guide).
//
// Fed from the control thread with running totals the audio thread publishes (the sum of squares
// of every speaker sample so far and the number of frames): the meter keeps one snapshot a second
// for the last hour in a fixed ring (no allocation after construction).

#include <cstdint>
#include <optional>
#include <vector>

namespace sas::kiosk {

class ExposureMeter {
 public:
  static constexpr double kHourS = 3600.0;

  ExposureMeter();

  // `energy` and `frames` are the audio side's running totals (never decreasing); `in_visit`
  // whether a visitor is at the box (a visit runs from the first touch to the attract screen).
  void Update(std::int64_t now_ns, double energy, std::uint64_t frames, bool in_visit);

  // Leq (dBFS RMS) over the last hour, or over what there is of it; empty before any audio.
  std::optional<double> LastHourDb() const;
  // Leq over the visit going on, or else the last finished one; empty before the first visit.
  std::optional<double> LastVisitDb() const;

 private:
  struct Snapshot {
    std::int64_t time_ns = 0;
    double energy = 0.0;
    std::uint64_t frames = 0;
  };
  static std::optional<double> Leq(const Snapshot& from, const Snapshot& to);

  std::vector<Snapshot> ring_;  // one a second, oldest overwritten
  std::size_t next_ = 0, count_ = 0;
  Snapshot latest_{};  // valid once count_ > 0
  bool in_visit_ = false;
  Snapshot visit_start_{}, visit_end_{};
  bool have_visit_ = false;
};

}  // namespace sas::kiosk

// The speaker's exposure over the last visit and the last hour (exposure_meter.h).
#include "kiosk/exposure_meter.h"

#include <algorithm>
#include <cmath>

namespace sas::kiosk {

namespace {
constexpr std::int64_t kSnapshotNs = 1'000'000'000;
}

ExposureMeter::ExposureMeter() : ring_(static_cast<std::size_t>(kHourS) + 2) {}

void ExposureMeter::Update(std::int64_t now_ns, double energy, std::uint64_t frames,
                           bool in_visit) {
  latest_ = {now_ns, energy, frames};
  if (count_ == 0 ||
      now_ns - ring_[(next_ + ring_.size() - 1) % ring_.size()].time_ns >= kSnapshotNs) {
    ring_[next_] = latest_;
    next_ = (next_ + 1) % ring_.size();
    if (count_ < ring_.size()) ++count_;
  }
  if (in_visit && !in_visit_) {
    visit_start_ = latest_;
    have_visit_ = true;
  }
  if (!in_visit && in_visit_) visit_end_ = latest_;
  in_visit_ = in_visit;
}

std::optional<double> ExposureMeter::Leq(const Snapshot& from, const Snapshot& to) {
  if (to.frames <= from.frames) return std::nullopt;
  const double mean_square =
      (to.energy - from.energy) / static_cast<double>(to.frames - from.frames);
  return 10.0 * std::log10(std::max(mean_square, 1e-30));
}

std::optional<double> ExposureMeter::LastHourDb() const {
  if (count_ == 0) return std::nullopt;
  // The oldest snapshot still inside the hour (the ring holds a little over an hour).
  const std::int64_t limit = latest_.time_ns - static_cast<std::int64_t>(kHourS * 1e9);
  const std::size_t oldest = (next_ + ring_.size() - count_) % ring_.size();
  for (std::size_t k = 0; k < count_; ++k) {
    const Snapshot& s = ring_[(oldest + k) % ring_.size()];
    if (s.time_ns >= limit) return Leq(s, latest_);
  }
  return std::nullopt;
}

std::optional<double> ExposureMeter::LastVisitDb() const {
  if (!have_visit_) return std::nullopt;
  return Leq(visit_start_, in_visit_ ? latest_ : visit_end_);
}

}  // namespace sas::kiosk

// Per-stroke loudness-matching corrections and the pen's smoothed stroke (see stroke_gain.h).
#include "levels/stroke_gain.h"

#include <algorithm>
#include <cmath>

namespace sas::kiosk {
namespace {

// Where `x` lies on `axis` (ascending): the lower index and the fraction towards the next one,
// held at the ends. `log_axis`: interpolate in log x.
void Locate(const std::vector<double>& axis, double x, bool log_axis, std::size_t* i,
            double* frac) {
  *i = 0;
  *frac = 0.0;
  if (axis.size() < 2 || !(x > axis.front())) return;
  if (x >= axis.back()) {
    *i = axis.size() - 2;
    *frac = 1.0;
    return;
  }
  while (*i + 2 < axis.size() && x >= axis[*i + 1]) ++*i;
  const auto f = [log_axis](double v) { return log_axis ? std::log(v) : v; };
  *frac = (f(x) - f(axis[*i])) / (f(axis[*i + 1]) - f(axis[*i]));
}

}  // namespace

StrokeCorrection InterpolateLevels(const surface::StrokeLevelTable& table, synth::ProbeStyle style,
                                   double width_mm, double speed_mm_s, double pressure,
                                   LevelBlend sound_blend) {
  const int s = style == synth::ProbeStyle::kRub                          ? 1
                : style == synth::ProbeStyle::kRoll && table.styles() > 2 ? 2
                                                                          : 0;
  const auto& widths = table.widths_mm(s);
  if (widths.empty() || table.speeds_mm_s.empty() || table.pressures.empty()) return {};
  const auto finite = [](double v) { return std::isfinite(v) ? v : 0.0; };
  std::size_t wi = 0, vi = 0, pi = 0;
  double wf = 0.0, vf = 0.0, pf = 0.0;
  Locate(widths, finite(width_mm), false, &wi, &wf);
  Locate(table.speeds_mm_s, finite(speed_mm_s), true, &vi, &vf);
  Locate(table.pressures, finite(pressure), false, &pi, &pf);
  const std::size_t w1 = std::min(wi + 1, widths.size() - 1);
  const std::size_t v1 = std::min(vi + 1, table.speeds_mm_s.size() - 1);
  const std::size_t p1 = std::min(pi + 1, table.pressures.size() - 1);
  const auto at = [&](const std::vector<double>& values, LevelBlend blend) {
    const bool power = blend == LevelBlend::kPower;
    const auto value = [&](std::size_t w, std::size_t v, std::size_t p) {
      const double db = values[table.Index(s, w, v, p)];
      return power ? std::pow(10.0, db / 10.0) : db;
    };
    const auto in_width = [&](std::size_t w) {
      const double a = value(w, vi, pi) * (1.0 - pf) + value(w, vi, p1) * pf;
      const double b = value(w, v1, pi) * (1.0 - pf) + value(w, v1, p1) * pf;
      return a * (1.0 - vf) + b * vf;
    };
    const double blended = in_width(wi) * (1.0 - wf) + in_width(w1) * wf;
    return power ? 10.0 * std::log10(blended) : blended;
  };
  return {at(table.sound_lufs, sound_blend), at(table.haptic_rms_db, LevelBlend::kDecibels)};
}

double ReferenceLevel(std::vector<double> levels) {
  if (levels.empty()) return 0.0;
  std::sort(levels.begin(), levels.end());
  const std::size_t n = levels.size();
  const double median = n % 2 == 1 ? levels[n / 2] : 0.5 * (levels[n / 2 - 1] + levels[n / 2]);
  const double lo = levels.front(), hi = levels.back();
  if (hi - lo > 2.0 * kMaxStrokeCorrectionDb) return 0.5 * (lo + hi);  // none can: halfway
  return std::clamp(median, hi - kMaxStrokeCorrectionDb, lo + kMaxStrokeCorrectionDb);
}

StrokeGainMap::StrokeGainMap(const std::vector<const surface::StrokeLevelTable*>& tables) {
  const surface::StrokeLevelTable* first = nullptr;
  for (const auto* table : tables) {
    if (table != nullptr) {
      first = table;
      break;
    }
  }
  levels_.resize(tables.size());
  if (first == nullptr) return;
  reference_ = *first;
  std::vector<const surface::StrokeLevelTable*> matched;
  for (const auto* table : tables) {
    if (table != nullptr && table->SameGrid(*first)) matched.push_back(table);
  }
  matched_ = static_cast<int>(matched.size());
  std::vector<double> sound, haptic;
  for (std::size_t k = 0; k < reference_.sound_lufs.size(); ++k) {
    sound.clear();
    haptic.clear();
    for (const auto* table : matched) {
      sound.push_back(table->sound_lufs[k]);
      haptic.push_back(table->haptic_rms_db[k]);
    }
    reference_.sound_lufs[k] = ReferenceLevel(sound);
    reference_.haptic_rms_db[k] = ReferenceLevel(haptic);
  }
  for (std::size_t t = 0; t < tables.size(); ++t) {
    if (tables[t] != nullptr && tables[t]->SameGrid(*first)) levels_[t] = *tables[t];
  }
}

StrokeCorrection StrokeGainMap::Correction(int texture, synth::ProbeStyle style, double width_mm,
                                           double speed_mm_s, double pressure) const {
  if (texture < 0 || texture >= static_cast<int>(levels_.size())) return {};
  const auto& own = levels_[static_cast<std::size_t>(texture)];
  if (own.sound_lufs.empty()) return {};
  const StrokeCorrection level =
      InterpolateLevels(own, style, width_mm, speed_mm_s, pressure, LevelBlend::kPower);
  const StrokeCorrection reference =
      InterpolateLevels(reference_, style, width_mm, speed_mm_s, pressure, LevelBlend::kPower);
  StrokeCorrection c{reference.sound_db - level.sound_db, reference.haptic_db - level.haptic_db};
  c.sound_db = std::clamp(c.sound_db, -kMaxStrokeCorrectionDb, kMaxStrokeCorrectionDb);
  c.haptic_db = std::clamp(c.haptic_db, -kMaxStrokeCorrectionDb, kMaxStrokeCorrectionDb);
  return c;
}

void StrokeTracker::Update(bool tip_down, bool has_speed, double speed_mm_s, double pressure,
                           double dt_s) {
  const bool speed_ok =
      has_speed && std::isfinite(speed_mm_s) && speed_mm_s >= 0.0 && speed_mm_s <= kMaxPenSpeedMmS;
  if (!std::isfinite(pressure)) pressure = pressure_;
  if (!tip_down) {
    down_ = false;  // hold the last values until the next stroke lands
    return;
  }
  if (!down_) {  // touch-down: start from this sample (and the hover's speed, when there is one)
    down_ = true;
    valid_ = true;
    pressure_ = pressure;
    if (speed_ok) speed_mm_s_ = speed_mm_s;
    return;
  }
  const double a = 1.0 - std::exp(-std::max(dt_s, 0.0) / kStrokeSmoothingS);
  if (speed_ok) speed_mm_s_ += a * (speed_mm_s - speed_mm_s_);
  pressure_ += a * (pressure - pressure_);
}

}  // namespace sas::kiosk

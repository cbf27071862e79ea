// Profile slots (see profile_slots.h).
#include "surface/profile_slots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "surface/image_loader.h"  // LoadError

namespace sas::surface {

const ProfileSlots::Slot& ProfileSlots::at(int slot) const {
  if (slot < 0 || slot >= kSlotCount)
    throw std::out_of_range("profile slot " + std::to_string(slot));
  return slots_[static_cast<std::size_t>(slot)];
}

void ProfileSlots::Store(int slot, std::string label, HeightField field) {
  at(slot);
  if (field.empty()) throw std::invalid_argument("profile slot: empty field");
  slots_[static_cast<std::size_t>(slot)] = {std::move(label),
                                            std::make_shared<const HeightField>(std::move(field))};
}

std::shared_ptr<const HeightField> ProfileSlots::Recall(int slot) const {
  return at(slot).field;
}
const std::string& ProfileSlots::label(int slot) const {
  return at(slot).label;
}
bool ProfileSlots::occupied(int slot) const {
  return at(slot).field != nullptr;
}
void ProfileSlots::Clear(int slot) {
  at(slot);
  slots_[static_cast<std::size_t>(slot)] = {};
}

double ProfileSlots::SaveToDisk(int slot, const std::string& path) const {
  const auto field = at(slot).field;
  if (!field)
    throw LoadError("profile slot " + std::to_string(slot) + " is empty: nothing to save");
  const double pitch_mm = field->pitch_m() * 1e3;
  if (field->height() == 1) {
    std::ofstream out(path);
    if (!out) throw LoadError("'" + path + "': cannot be written");
    out << "position_mm,height_mm\n";
    char line[64];
    for (int x = 0; x < field->width(); ++x) {
      std::snprintf(line, sizeof line, "%.6f,%.9g\n", x * pitch_mm, field->at(x, 0) * 1e3);
      out << line;
    }
    if (!out) throw LoadError("'" + path + "': write failed");
    const auto [lo, hi] = std::minmax_element(field->heights_m().begin(), field->heights_m().end());
    return std::max(std::fabs(*lo), std::fabs(*hi)) * 1e3;
  }
  const float top = *std::max_element(field->heights_m().begin(), field->heights_m().end());
  const double full_scale_mm = top > 0.0f ? top * 1e3 : 1.0;
  cv::Mat png(field->height(), field->width(), CV_16UC1);
  for (int y = 0; y < field->height(); ++y) {
    auto* row = png.ptr<std::uint16_t>(y);
    for (int x = 0; x < field->width(); ++x) {
      const double v = std::clamp(field->at(x, y) * 1e3 / full_scale_mm, 0.0, 1.0);
      row[x] = static_cast<std::uint16_t>(std::lround(v * 65535.0));
    }
  }
  bool ok = false;
  try {
    ok = cv::imwrite(path, png);
  } catch (const cv::Exception&) {
    ok = false;
  }
  if (!ok) throw LoadError("'" + path + "': cannot be written as a 16-bit PNG");
  return full_scale_mm;
}

}  // namespace sas::surface

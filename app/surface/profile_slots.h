#pragma once
// The six profile slots of the paper's GUI (§4: "Up to six different roughness profiles can be
// recorded as audio signals and recalled, to drive the synthesis engine"). In the kiosk one slot
// holds the visitor's voice. Slots live in memory only; writing one to disk is an explicit staff
// action (SaveToDisk), never a side effect of storing.
//
// A slot holds a shared, immutable HeightField so the audio side can keep reading a surface that
// the control side has since replaced: the old one lives until its last user lets go.

#include <array>
#include <memory>
#include <string>

#include "surface/height_field.h"

namespace sas::surface {

class ProfileSlots {
 public:
  static constexpr int kSlotCount = 6;

  // Throws std::out_of_range for a slot outside [0, kSlotCount) and invalid_argument for an empty
  // field.
  void Store(int slot, std::string label, HeightField field);
  std::shared_ptr<const HeightField> Recall(int slot) const;  // nullptr when empty
  const std::string& label(int slot) const;
  bool occupied(int slot) const;
  void Clear(int slot);

  // Writes the slot: a one-row profile as CSV "position_mm,height_mm" (readable again with
  // VibrationProfileFromFile), a 2-D field as a 16-bit PNG whose full scale is returned in mm
  // (readable with LoadHeightMapPng). Throws LoadError when the slot is empty or writing fails.
  double SaveToDisk(int slot, const std::string& path) const;

 private:
  struct Slot {
    std::string label;
    std::shared_ptr<const HeightField> field;
  };
  const Slot& at(int slot) const;
  std::array<Slot, kSlotCount> slots_{};
};

}  // namespace sas::surface

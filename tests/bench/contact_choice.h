#pragma once
// contact_bench --choose: for every shipped material (textures/materials/*.toml), the cheapest
// contact policy (scheme, sub-steps per contact, sustained sub-steps) that meets the kiosk's error
// budget (calibration/contact_budget.h), per style and for the material; writes the table the
// material loader applies (app/files/contact_choices.inc) and docs/contact-budget.md.
#include <string>

namespace sas::bench {

struct ChooseOptions {
  std::string materials_dir;  // the shipped materials
  std::string table_path;     // the generated table ("-": not written)
  std::string docs_path;      // the budget's figures ("-": not written)
  int reps = 3;               // best of N CPU times for the costs
};

int RunChoose(const ChooseOptions& options);

}  // namespace sas::bench

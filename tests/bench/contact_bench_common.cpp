// The contact benchmark's shared helpers (contact_bench_common.h).
#include "contact_bench_common.h"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <vector>

namespace sas::bench {

double CpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::string Sci(double v, int digits) {
  if (!(v > 0)) return v == 0 ? "0" : "-";
  char s[32];
  std::snprintf(s, sizeof s, "%.*e", digits, v);
  return s;
}

synth::ResonatorParams SteelPlate32() {
  const double e_mod = 200e9, rho = 7850.0, nu = 0.3, h = 0.003, a = 0.25, b = 0.18, eta = 8e-4;
  const double c = 0.5 * std::numbers::pi * h * std::sqrt(e_mod / (12.0 * rho * (1.0 - nu * nu)));
  struct Mode {
    double f, mass, gain;
  };
  std::vector<Mode> modes;
  for (int m = 1; m <= 30; ++m) {
    for (int n = 1; n <= 30; ++n) {
      const double f = c * ((m / a) * (m / a) + (n / b) * (n / b));
      if (f >= 0.45 * kFs) continue;
      const double shape_contact =
          std::sin(m * std::numbers::pi * 0.37) * std::sin(n * std::numbers::pi * 0.41);
      const double gain =
          std::sin(m * std::numbers::pi * 0.21) * std::sin(n * std::numbers::pi * 0.67);
      if (std::fabs(gain) < 0.05) continue;
      const double mass = rho * h * a * b / 4.0 / std::max(shape_contact * shape_contact, 0.09);
      modes.push_back({f, mass, gain});
    }
  }
  std::sort(modes.begin(), modes.end(), [](const Mode& x, const Mode& y) { return x.f < y.f; });
  synth::ResonatorParams params;
  params.mode_count = std::min<int>(32, static_cast<int>(modes.size()));
  for (int i = 0; i < params.mode_count; ++i) {
    const Mode& m = modes[static_cast<std::size_t>(i)];
    params.modes[static_cast<std::size_t>(i)] =
        synth::ModeParams{m.f, 1.0 / (std::numbers::pi * m.f * eta), m.mass, m.gain};
  }
  return params;
}

}  // namespace sas::bench

#pragma once
// In-place iterative radix-2 FFT (Cooley–Tukey, decimation in time) on split real/imaginary
// arrays, for spectra in tests and benchmarks: written here, independent of the filters it checks.
// The size must be a power of two.

#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>
#include <vector>

namespace sas::test {

inline void FftInPlace(std::vector<double>& re, std::vector<double>& im) {
  const std::size_t n = re.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {  // bit reversal
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) {
      std::swap(re[i], re[j]);
      std::swap(im[i], im[j]);
    }
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double angle = -2.0 * std::numbers::pi / static_cast<double>(len);
    for (std::size_t i = 0; i < n; i += len) {
      for (std::size_t k = 0; k < len / 2; ++k) {
        const double wr = std::cos(angle * static_cast<double>(k));
        const double wi = std::sin(angle * static_cast<double>(k));
        const std::size_t a = i + k, b = i + k + len / 2;
        const double tr = re[b] * wr - im[b] * wi, ti = re[b] * wi + im[b] * wr;
        re[b] = re[a] - tr;
        im[b] = im[a] - ti;
        re[a] += tr;
        im[a] += ti;
      }
    }
  }
}

}  // namespace sas::test

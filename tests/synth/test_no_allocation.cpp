// Scene::Process() allocates nothing (this executable replaces the global
// operator new/delete and counts calls while rendering) and runs with denormals flushed, leaving
// the caller's floating-point mode as it found it. Its own executable because the replacement
// operators are global.
#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <new>
#include <vector>

#include "synth/scene.h"
#include "synth_test_support.h"

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#endif

namespace {
std::atomic<long> g_allocations{0};
std::atomic<bool> g_counting{false};

void* CountedAlloc(std::size_t size) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
  void* p = std::malloc(size == 0 ? 1 : size);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
void* CountedAlignedAlloc(std::size_t size, std::align_val_t align) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1);
  const auto a = static_cast<std::size_t>(align);
  void* p = std::aligned_alloc(a, (size + a - 1) / a * a);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
}  // namespace

void* operator new(std::size_t size) {
  return CountedAlloc(size);
}
void* operator new[](std::size_t size) {
  return CountedAlloc(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return CountedAlloc(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return CountedAlloc(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t align) {
  return CountedAlignedAlloc(size, align);
}
void* operator new[](std::size_t size, std::align_val_t align) {
  return CountedAlignedAlloc(size, align);
}
// Every delete form frees through one helper rather than calling operator delete(void*): GCC 12
// at -O3 (the Release build) inlines that call into e.g. delete[] and then flags it under
// -Wmismatched-new-delete as freeing new[] memory with plain delete.
namespace {
void CountedFree(void* p) noexcept {
  if (g_counting.load(std::memory_order_relaxed) && p != nullptr) g_allocations.fetch_add(1);
  std::free(p);
}
}  // namespace
void operator delete(void* p) noexcept {
  CountedFree(p);
}
void operator delete[](void* p) noexcept {
  CountedFree(p);
}
void operator delete(void* p, std::size_t) noexcept {
  CountedFree(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  CountedFree(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  CountedFree(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  CountedFree(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  CountedFree(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  CountedFree(p);
}

using namespace sas::synth;

namespace {

MaterialParams Glass() {
  MaterialParams m;
  m.resonator.mode_count = 32;
  for (int i = 0; i < 32; ++i) {
    auto& mode = m.resonator.modes[static_cast<std::size_t>(i)];
    mode.frequency_hz = 400.0 * (i + 1) * (1.0 + 0.03 * i);
    mode.decay_s = 1.5 / (1.0 + 0.3 * i);
    mode.mass_kg = 0.05;
    mode.gain = 1.0 / (1.0 + i);
  }
  m.impact.stiffness = 5e7;
  m.friction.noise_coefficient = 0.5;
  return m;
}

}  // namespace

TEST_CASE("the counting allocator sees allocations (so a zero below means something)", "[dsp]") {
  g_allocations = 0;
  g_counting = true;
  auto* v = new std::vector<int>(100);
  delete v;
  g_counting = false;
  CHECK(g_allocations.load() >= 2);
}

TEST_CASE("Process allocates nothing across 10 s of rendering with every kind of command",
          "[dsp][render]") {
  std::vector<float> profile(8000);
  for (std::size_t i = 0; i < profile.size(); ++i)
    profile[i] = static_cast<float>(30e-6 * (1.0 + std::sin(0.2 * static_cast<double>(i))));
  test::OwnedField field(8000, 1, 0.153e-3, profile);
  Scene scene;
  scene.Init(48000.0);
  scene.Prepare(Glass(), OutputParams{}, field.view);
  std::vector<float> out(2 * 128);
  std::vector<ProbeCommand> commands(3);
  g_allocations = 0;
  g_counting = true;
  for (int block = 0; block < 48000 * 10 / 128; ++block) {
    int count = 0;
    if (block % 50 == 0) {
      ProbeCommand& c = commands[static_cast<std::size_t>(count++)];
      c = ProbeCommand{};
      c.frame_offset = static_cast<std::uint32_t>(block % 128);
      c.tip_down = (block / 50) % 4 != 3;
      c.x_m = 0.01 + 1e-4 * block;
      c.velocity_mps = 0.05 * ((block / 50) % 7);
      c.normal_force_n = 0.5;
      c.penetration_m = 50e-6;
      c.width_mm = 0.3 + (block / 50) % 10;
      c.style = static_cast<ProbeStyle>((block / 50) % 3);
      c.burst_impulse_n_s = (block / 50) % 5 == 0 ? 2e-4 : 0.0;
    }
    scene.Process(commands.data(), count, out.data(), 128);
    (void)scene.IsIdle();
    (void)scene.TotalEnergy();
  }
  g_counting = false;
  CHECK(g_allocations.load() == 0);
}

TEST_CASE("denormals are flushed inside Process and the caller's floating-point mode is restored",
          "[dsp]") {
#if defined(__SSE__) || defined(__x86_64__)
  const unsigned before = _mm_getcsr();
#endif
  MaterialParams m;
  m.resonator.mode_count = 1;
  m.resonator.modes[0] = ModeParams{50.0, 0.05, 0.01, 1.0};  // decays 8.7 dB per 100 ms
  m.friction.enabled = false;
  Scene scene;
  scene.Init(48000.0);
  scene.Prepare(m, OutputParams{}, HeightFieldView{});
  ProbeCommand burst;
  burst.burst_impulse_n_s = 1e-3;
  std::vector<float> out(2 * 48000);
  long subnormal = 0, nonzero = 0;
  // 60 s of ring-down: the mode passes 1e-38 (float) after ~4 s and 1e-308 (double) after ~35 s.
  for (int second = 0; second < 60; ++second) {
    scene.Process(second == 0 ? &burst : nullptr, second == 0 ? 1 : 0, out.data(), 48000);
    for (float s : out) {
      if (s != 0.0f) ++nonzero;
      if (s != 0.0f && std::fabs(s) < 1.17549435e-38f) ++subnormal;
    }
#if defined(__SSE__) || defined(__x86_64__)
    // Control bits (rounding, FTZ, DAZ, masks) restored; the sticky status flags (bits 0-5)
    // are set by any inexact operation, including this test's own.
    REQUIRE((_mm_getcsr() & ~0x3Fu) == (before & ~0x3Fu));
#endif
  }
  CHECK(nonzero > 0);
  CHECK(subnormal == 0);
  CHECK(scene.ResonatorEnergy() == 0.0);  // flushed to exactly zero, not left subnormal
}

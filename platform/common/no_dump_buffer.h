#pragma once
// Memory kept out of core dumps, for the visitor's voice: it lives in RAM only, never on disk, so
// a crash during a visit must not write it into a core file either. Pages come straight from
// mmap (never from the heap, whose pages hold other data and are handed out again) and are
// marked madvise(MADV_DONTDUMP); they are zeroed (explicit_bzero, which the compiler may not
// drop) on Wipe and before they are unmapped.
//
// NoDumpBuffer<T>: a fixed-capacity, move-only RAII buffer allocated once at set-up (the voice
// recorder's capture buffer; never allocated in the audio callback). NoDumpMemory(): the same
// pages behind a std::pmr::memory_resource, one mapping per allocation, for the few large
// allocator-aware buffers derived from a recording (the voice's sound image and height field).

#include <cstddef>
#include <memory_resource>
#include <span>
#include <type_traits>
#include <utility>

namespace sas::platform {

// Maps at least `bytes` of zeroed anonymous memory marked MADV_DONTDUMP. Throws std::bad_alloc
// when the mapping or the mark fails (memory that would reach a dump is not handed out).
void* MapNoDump(std::size_t bytes);
// Zeroes and unmaps memory from MapNoDump (`bytes` as passed to it). Null is ignored.
void UnmapNoDump(void* data, std::size_t bytes) noexcept;
// Zeroes `bytes` at `data` in a way the compiler may not optimise away.
void SecureZero(void* data, std::size_t bytes) noexcept;

template <typename T>
class NoDumpBuffer {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "raw samples only: the pages are zeroed and unmapped, never destructed");

 public:
  NoDumpBuffer() = default;
  // `capacity` elements, zeroed. Set-up only (it maps memory). Throws std::bad_alloc.
  explicit NoDumpBuffer(std::size_t capacity)
      : data_(capacity ? static_cast<T*>(MapNoDump(capacity * sizeof(T))) : nullptr),
        capacity_(capacity) {}
  ~NoDumpBuffer() { UnmapNoDump(data_, capacity_ * sizeof(T)); }
  NoDumpBuffer(const NoDumpBuffer&) = delete;
  NoDumpBuffer& operator=(const NoDumpBuffer&) = delete;
  NoDumpBuffer(NoDumpBuffer&& other) noexcept
      : data_(std::exchange(other.data_, nullptr)), capacity_(std::exchange(other.capacity_, 0)) {}
  NoDumpBuffer& operator=(NoDumpBuffer&& other) noexcept {
    if (this != &other) {
      UnmapNoDump(data_, capacity_ * sizeof(T));
      data_ = std::exchange(other.data_, nullptr);
      capacity_ = std::exchange(other.capacity_, 0);
    }
    return *this;
  }

  // Overwrites every element with zero bytes. No allocation, no lock.
  void Wipe() noexcept { SecureZero(data_, capacity_ * sizeof(T)); }

  T* data() noexcept { return data_; }
  const T* data() const noexcept { return data_; }
  std::size_t size() const noexcept { return capacity_; }
  bool empty() const noexcept { return capacity_ == 0; }
  T& operator[](std::size_t i) noexcept { return data_[i]; }
  const T& operator[](std::size_t i) const noexcept { return data_[i]; }
  std::span<T> span() noexcept { return {data_, capacity_}; }
  std::span<const T> span() const noexcept { return {data_, capacity_}; }

 private:
  T* data_ = nullptr;
  std::size_t capacity_ = 0;
};

// A process-wide memory resource over MapNoDump/UnmapNoDump (each allocation its own mapping,
// zeroed when released). Never destroyed, so memory from it may outlive any owner's order of
// destruction. Meant for a few large buffers allocated off the audio thread.
std::pmr::memory_resource* NoDumpMemory();

}  // namespace sas::platform

#pragma once
// Single-producer single-consumer lock-free ring of small trivially-copyable messages:
// the pen thread -> control thread, switch threads -> control thread, and the control side ->
// the audio player. Fixed capacity (a power of two) chosen at compile time: no allocation, no
// locks, wait-free on both sides. The classic Lamport ring with acquire/release indices; each side
// caches the other's index to avoid touching the shared cache line on every call (the idea behind
// choc::fifo and rigtorp's SPSCQueue; written from scratch here).

#include <array>
#include <atomic>
#include <cstddef>
#include <type_traits>

namespace sas {

template <typename T, std::size_t kCapacity>
class SpscQueue {
  static_assert(std::is_trivially_copyable_v<T>, "messages are small PODs");
  static_assert(kCapacity >= 2 && (kCapacity & (kCapacity - 1)) == 0, "capacity: power of two");

 public:
  SpscQueue() = default;
  SpscQueue(const SpscQueue&) = delete;
  SpscQueue& operator=(const SpscQueue&) = delete;

  // Producer side. False (message dropped) when full: the producer never blocks.
  bool TryPush(const T& value) noexcept {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_cache_ == kCapacity) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (head - tail_cache_ == kCapacity) return false;
    }
    slots_[head & kMask] = value;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer side. False when empty.
  bool TryPop(T& out) noexcept {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_cache_) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (tail == head_cache_) return false;
    }
    out = slots_[tail & kMask];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  // Approximate from either side; exact when the other side is idle.
  std::size_t SizeApprox() const noexcept {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }
  static constexpr std::size_t Capacity() { return kCapacity; }

 private:
  static constexpr std::size_t kMask = kCapacity - 1;
  // Producer and consumer indices live on separate cache lines (no false sharing).
  alignas(64) std::atomic<std::size_t> head_{0};
  std::size_t tail_cache_ = 0;  // producer's view of tail_
  alignas(64) std::atomic<std::size_t> tail_{0};
  std::size_t head_cache_ = 0;  // consumer's view of head_
  alignas(64) std::array<T, kCapacity> slots_{};
};

}  // namespace sas

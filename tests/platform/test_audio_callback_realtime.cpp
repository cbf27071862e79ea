// The audio callback path allocates nothing and takes no lock (either can stall it).
// This executable replaces the global operator new/delete and interposes pthread's lock
// functions; both count calls made on a thread while its `t_counting` flag is set. The tests then
// call the exact functions PortAudio calls on its audio thread (output: callback core + a
// renderer that drains an SPSC queue of commands and synthesises two channels; input: the voice
// recorder) thousands of times with counting on. A self-check proves the counters see an
// allocation and a lock when there is one, so a zero is a real zero.
#include <dlfcn.h>
#include <pthread.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <mutex>
#include <new>
#include <vector>

#include "common/spsc_queue.h"
#include "platform/audio/portaudio_callbacks.h"

namespace {

thread_local bool t_counting = false;
std::atomic<long> g_news{0};
std::atomic<long> g_locks{0};

void* CountedAlloc(std::size_t size) {
  if (t_counting) g_news.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

template <typename Fn>
Fn Next(const char* name) {
  return reinterpret_cast<Fn>(dlsym(RTLD_NEXT, name));
}

using MutexFn = int (*)(pthread_mutex_t*);
using RwFn = int (*)(pthread_rwlock_t*);
MutexFn real_mutex_lock = Next<MutexFn>("pthread_mutex_lock");
MutexFn real_mutex_trylock = Next<MutexFn>("pthread_mutex_trylock");
RwFn real_rdlock = Next<RwFn>("pthread_rwlock_rdlock");
RwFn real_wrlock = Next<RwFn>("pthread_rwlock_wrlock");

}  // namespace

void* operator new(std::size_t size) {
  return CountedAlloc(size);
}
void* operator new[](std::size_t size) {
  return CountedAlloc(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (t_counting) g_news.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  if (t_counting) g_news.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(size == 0 ? 1 : size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

extern "C" {
int pthread_mutex_lock(pthread_mutex_t* m) {
  if (t_counting) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real_mutex_lock ? real_mutex_lock(m) : 0;
}
int pthread_mutex_trylock(pthread_mutex_t* m) {
  if (t_counting) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real_mutex_trylock ? real_mutex_trylock(m) : 0;
}
int pthread_rwlock_rdlock(pthread_rwlock_t* l) {
  if (t_counting) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real_rdlock ? real_rdlock(l) : 0;
}
int pthread_rwlock_wrlock(pthread_rwlock_t* l) {
  if (t_counting) g_locks.fetch_add(1, std::memory_order_relaxed);
  return real_wrlock ? real_wrlock(l) : 0;
}
}

namespace {

struct Counts {
  long news;
  long locks;
};

template <typename Fn>
Counts Counted(Fn&& fn) {
  const long news0 = g_news.load();
  const long locks0 = g_locks.load();
  t_counting = true;
  fn();
  t_counting = false;
  return {g_news.load() - news0, g_locks.load() - locks0};
}

// Small POD command, like the UI -> audio ProbeCommand.
struct Command {
  double frequency_hz;
  float gain;
};

// A renderer doing what the kiosk's does in kind: drain commands, run per-sample state, write
// both channels.
class SynthLikeRenderer final : public sas::platform::AudioRenderer {
 public:
  sas::SpscQueue<Command, 64> commands;
  void Render(float* out, int frames, int channels) noexcept override {
    Command c{};
    while (commands.TryPop(c)) {
      increment_ = 2.0 * 3.14159265358979 * c.frequency_hz / 48000.0;
      gain_ = c.gain;
    }
    for (int i = 0; i < frames; ++i) {
      phase_ += increment_;
      const float s = gain_ * static_cast<float>(std::sin(phase_));
      out[i * channels] = s;
      out[i * channels + 1] = 0.5f * s;
    }
  }

 private:
  double phase_ = 0.0;
  double increment_ = 0.01;
  float gain_ = 0.1f;
};

}  // namespace

TEST_CASE("allocation and lock counters see an allocation and a lock on the counting thread",
          "[platform]") {
  std::mutex mutex;
  const Counts counts = Counted([&] {
    void* volatile p = ::operator new(16);
    ::operator delete(p);
    std::lock_guard lock(mutex);
  });
  CHECK(counts.news == 1);
  CHECK(counts.locks == 1);
  // Not counted when the flag is off (another thread's work is not ours).
  const long before = g_news.load();
  void* volatile q = ::operator new(16);
  ::operator delete(q);
  CHECK(g_news.load() == before);
}

TEST_CASE("PortAudio output callback path allocates nothing and takes no lock", "[platform]") {
  SynthLikeRenderer renderer;
  sas::platform::AudioCallbackCore core(renderer);
  sas::platform::detail::OutputCallbackContext context{&core, 2};
  std::vector<float> buffer(128 * 2);
  int commands_sent = 0;
  const Counts counts = Counted([&] {
    for (int block = 0; block < 5000; ++block) {
      if (block % 10 == 0) {
        // The producer side lives on another thread in the kiosk; here it only feeds the queue.
        t_counting = false;
        renderer.commands.TryPush({200.0 + block, 0.2f});
        ++commands_sent;
        t_counting = true;
      }
      const PaStreamCallbackFlags flags = block % 1000 == 0 ? paOutputUnderflow : 0;
      sas::platform::detail::PortAudioOutputCallback(nullptr, buffer.data(), 128, nullptr, flags,
                                                     &context);
    }
  });
  CHECK(counts.news == 0);
  CHECK(counts.locks == 0);
  const auto stats = core.Stats();
  CHECK(stats.callbacks == 5000);
  CHECK(stats.xruns == 5);
  CHECK(commands_sent == 500);
  CHECK(buffer[0] != 0.0f);  // the renderer really ran
}

TEST_CASE("PortAudio input callback path allocates nothing and takes no lock", "[platform]") {
  sas::platform::VoiceRecorderConfig config;
  config.max_duration_s = 5.0;
  sas::platform::VoiceRecorder recorder(config);
  sas::platform::detail::InputCallbackContext context{&recorder, 1};
  std::vector<float> input(256);
  for (std::size_t i = 0; i < input.size(); ++i) input[i] = 0.3f * std::sin(0.1f * float(i));
  recorder.Arm();
  const Counts counts = Counted([&] {
    for (int block = 0; block < 1200; ++block) {  // 6.4 s: past the 5 s buffer end
      sas::platform::detail::PortAudioInputCallback(input.data(), nullptr, 256, nullptr, 0,
                                                    &context);
    }
  });
  CHECK(counts.news == 0);
  CHECK(counts.locks == 0);
  CHECK(recorder.Recorded() == 5u * 48000u);
  CHECK(recorder.Level() > 0.25f);
}

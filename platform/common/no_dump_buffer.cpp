// Memory kept out of core dumps (see no_dump_buffer.h).
#include "platform/common/no_dump_buffer.h"

#include <sys/mman.h>
#include <unistd.h>

#include <cstring>
#include <new>

namespace sas::platform {
namespace {

std::size_t PageRounded(std::size_t bytes) {
  static const auto page = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
  return (bytes + page - 1) / page * page;
}

class NoDumpResource final : public std::pmr::memory_resource {
 private:
  void* do_allocate(std::size_t bytes, std::size_t alignment) override {
    // mmap returns page-aligned memory: any alignment up to a page holds.
    if (alignment > static_cast<std::size_t>(sysconf(_SC_PAGESIZE))) throw std::bad_alloc();
    return MapNoDump(bytes == 0 ? 1 : bytes);
  }
  void do_deallocate(void* p, std::size_t bytes, std::size_t /*alignment*/) override {
    UnmapNoDump(p, bytes == 0 ? 1 : bytes);
  }
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override {
    return this == &other;
  }
};

}  // namespace

void* MapNoDump(std::size_t bytes) {
  const std::size_t length = PageRounded(bytes);
  void* data = mmap(nullptr, length, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (data == MAP_FAILED) throw std::bad_alloc();
  if (madvise(data, length, MADV_DONTDUMP) != 0) {
    munmap(data, length);
    throw std::bad_alloc();
  }
  return data;
}

void UnmapNoDump(void* data, std::size_t bytes) noexcept {
  if (data == nullptr) return;
  const std::size_t length = PageRounded(bytes);
  SecureZero(data, length);
  munmap(data, length);
}

void SecureZero(void* data, std::size_t bytes) noexcept {
  if (data != nullptr && bytes != 0) explicit_bzero(data, bytes);
}

std::pmr::memory_resource* NoDumpMemory() {
  // Leaked on purpose: deallocations may come from static destructors after main returns.
  static auto* resource = new NoDumpResource();
  return resource;
}

}  // namespace sas::platform

#include "support/allocation_counter.hpp"

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
thread_local std::size_t g_allocations = 0;

void* allocate(std::size_t size, std::size_t alignment) {
  ++g_allocations;
  if (size == 0) size = 1;
  void* p = nullptr;
  if (alignment <= alignof(std::max_align_t)) {
    p = std::malloc(size);
  } else {
    const std::size_t rounded = (size + alignment - 1) / alignment * alignment;
    p = std::aligned_alloc(alignment, rounded);
  }
  if (p == nullptr) throw std::bad_alloc();
  return p;
}
}  // namespace

// In a program linked with --wrap=malloc every malloc call of the program and of the libraries it
// links statically comes here first; elsewhere __real_malloc stays null and this is never called.
extern "C" {
void* __real_malloc(std::size_t size) __attribute__((weak));
void* __wrap_malloc(std::size_t size);
}

namespace {
thread_local std::size_t g_mallocs = 0;
}  // namespace

extern "C" void* __wrap_malloc(std::size_t size) {
  ++g_mallocs;
  return __real_malloc(size);
}

namespace tpf::test {
std::size_t allocation_count() noexcept {
  return g_allocations;
}

std::size_t heap_allocation_count() noexcept {
  // The compiler takes malloc for a function that leaves other globals alone: read afresh.
  std::atomic_signal_fence(std::memory_order_seq_cst);
  return g_allocations + g_mallocs;
}

bool mallocs_are_counted() noexcept {
  const std::size_t before = heap_allocation_count();
  void* volatile p = std::malloc(16);
  std::free(p);
  return heap_allocation_count() != before;
}
}  // namespace tpf::test

void* operator new(std::size_t size) {
  return allocate(size, alignof(std::max_align_t));
}
void* operator new[](std::size_t size) {
  return allocate(size, alignof(std::max_align_t));
}
void* operator new(std::size_t size, std::align_val_t a) {
  return allocate(size, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t size, std::align_val_t a) {
  return allocate(size, static_cast<std::size_t>(a));
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size, alignof(std::max_align_t));
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return allocate(size, alignof(std::max_align_t));
  } catch (...) {
    return nullptr;
  }
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
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}

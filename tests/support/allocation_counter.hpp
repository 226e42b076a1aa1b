// Counts heap allocations made by the current thread, to prove that per-cycle code allocates
// nothing. Every test program links allocation_counter.cpp, which replaces the global operator new.
#pragma once

#include <cstddef>

namespace tpf::test {

/// Number of calls to any global operator new / malloc-family replacement made by this thread.
std::size_t allocation_count() noexcept;

/// Heap allocations of this thread: allocation_count() plus its malloc calls where they are
/// counted. Eigen's heap memory comes from std::malloc, which operator new does not see; a test
/// program linked with -Wl,--wrap=malloc (tpf_count_malloc, tests/CMakeLists.txt) counts them.
std::size_t heap_allocation_count() noexcept;

/// Whether this program counts malloc calls (it was linked with --wrap=malloc).
bool mallocs_are_counted() noexcept;

/// Counts the allocations made while it is alive:
///   AllocationCounter counter;  run_cycle();  EXPECT_EQ(counter.count(), 0u);
class AllocationCounter {
 public:
  AllocationCounter() noexcept : start_(allocation_count()) {}
  std::size_t count() const noexcept { return allocation_count() - start_; }

 private:
  std::size_t start_;
};

}  // namespace tpf::test

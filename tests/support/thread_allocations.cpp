#include "thread_allocations.hpp"

#include <cstdlib>
#include <new>

// Kept out of line: inlined, GCC would see the malloc/free pairing behind new/delete and warn.
namespace {
thread_local std::size_t g_allocations = 0;
}  // namespace

[[gnu::noinline]] void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}
[[gnu::noinline]] void operator delete(void* memory) noexcept { std::free(memory); }
[[gnu::noinline]] void operator delete(void* memory, std::size_t /*size*/) noexcept { std::free(memory); }

namespace robotd::testing {

std::size_t allocations_on_this_thread() { return g_allocations; }

}  // namespace robotd::testing

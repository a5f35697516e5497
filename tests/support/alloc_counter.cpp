// librobotd_alloc_counter.so: preloaded into robotd (LD_PRELOAD) to count heap allocations per
// thread. Every allocation entry point of glibc is interposed and forwarded to glibc's own
// implementation; operator new reaches malloc and is counted too. robotd's RT loop reads its
// thread's count through robotd_alloc_counter_thread_count() (see rt/allocation_probe.hpp).
#include <cstddef>
#include <cstdint>

extern "C" {
void* __libc_malloc(std::size_t size);                           // NOLINT(bugprone-reserved-identifier)
void* __libc_calloc(std::size_t count, std::size_t size);        // NOLINT(bugprone-reserved-identifier)
void* __libc_realloc(void* pointer, std::size_t size);           // NOLINT(bugprone-reserved-identifier)
void* __libc_memalign(std::size_t alignment, std::size_t size);  // NOLINT(bugprone-reserved-identifier)
void* __libc_valloc(std::size_t size);                           // NOLINT(bugprone-reserved-identifier)
void* __libc_pvalloc(std::size_t size);                          // NOLINT(bugprone-reserved-identifier)
}

namespace {
// initial-exec: the TLS slot exists before the first allocation, and reading it never allocates.
thread_local std::uint64_t allocations __attribute__((tls_model("initial-exec"))) = 0;
}  // namespace

extern "C" {

__attribute__((visibility("default"))) std::uint64_t robotd_alloc_counter_thread_count() { return allocations; }

__attribute__((visibility("default"))) void* malloc(std::size_t size) {
  ++allocations;
  return __libc_malloc(size);
}

__attribute__((visibility("default"))) void* calloc(std::size_t count, std::size_t size) {
  ++allocations;
  return __libc_calloc(count, size);
}

__attribute__((visibility("default"))) void* realloc(void* pointer, std::size_t size) {
  ++allocations;
  return __libc_realloc(pointer, size);
}

__attribute__((visibility("default"))) void* memalign(std::size_t alignment, std::size_t size) {
  ++allocations;
  return __libc_memalign(alignment, size);
}

__attribute__((visibility("default"))) void* aligned_alloc(std::size_t alignment, std::size_t size) {
  ++allocations;
  return __libc_memalign(alignment, size);
}

__attribute__((visibility("default"))) int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  ++allocations;
  void* pointer = __libc_memalign(alignment, size);
  if (pointer == nullptr) return 12;  // ENOMEM
  *out = pointer;
  return 0;
}

__attribute__((visibility("default"))) void* valloc(std::size_t size) {
  ++allocations;
  return __libc_valloc(size);
}

__attribute__((visibility("default"))) void* pvalloc(std::size_t size) {
  ++allocations;
  return __libc_pvalloc(size);
}

}  // extern "C"

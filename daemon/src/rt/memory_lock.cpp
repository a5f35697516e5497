#include "rt/memory_lock.hpp"

#include <cerrno>
#include <cstdint>
#include <link.h>
#include <sys/mman.h>
#include <system_error>
#include <unistd.h>

namespace robotd::rt {
namespace {

constexpr const char* kRemedy = "raise RLIMIT_MEMLOCK (LimitMEMLOCK=infinity) or grant CAP_IPC_LOCK";

struct SegmentLock {
  std::uintptr_t page = 0;
  std::string failure;
};

int lock_segments(dl_phdr_info* info, std::size_t /*size*/, void* data) {
  auto& lock = *static_cast<SegmentLock*>(data);
  for (ElfW(Half) i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& header = info->dlpi_phdr[i];
    if (header.p_type != PT_LOAD || header.p_memsz == 0) continue;
    const std::uintptr_t start = info->dlpi_addr + header.p_vaddr;
    const std::uintptr_t first_page = start & ~(lock.page - 1);
    // mlock faults the pages in (without MCL_ONFAULT's laziness) and keeps them. The loader hands
    // out addresses as integers, hence the cast.
    const auto* first = reinterpret_cast<const void*>(first_page);  // NOLINT(performance-no-int-to-ptr)
    if (mlock(first, start + header.p_memsz - first_page) != 0) {
      const char* name = info->dlpi_name[0] != '\0' ? info->dlpi_name : "the executable";
      lock.failure = std::string("mlock of ") + name + " failed (" + std::generic_category().message(errno) + "); ";
      return 1;
    }
  }
  return 0;
}

}  // namespace

std::string lock_memory() {
  if (mlockall(MCL_CURRENT | MCL_FUTURE | MCL_ONFAULT) == 0) return "";
  return std::string("mlockall failed (") + std::generic_category().message(errno) +
         "): pages may be swapped out under memory pressure; " + kRemedy;
}

std::string lock_loaded_objects() {
  SegmentLock lock{static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE)), {}};
  dl_iterate_phdr(lock_segments, &lock);
  if (lock.failure.empty()) return "";
  return lock.failure + "the loops' code may page-fault on its first run of a path; " + kRemedy;
}

}  // namespace robotd::rt

#include "driver/process_memory.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace spire {

void useHugePageHeap() {
#if defined(__GLIBC__) && defined(MADV_HUGEPAGE)
  // The reservation is address space only: pages are faulted in as malloc
  // hands them out, 2 MiB at a time once advised. 32 MiB is glibc's largest
  // mmap threshold.
  constexpr size_t kThreshold = size_t{32} << 20;
  constexpr uintptr_t kHugePage = uintptr_t{2} << 20;
  // glslang's large blocks must come from the advised heap, not from fresh
  // 4 KiB-faulted mmaps; freeing must not hand the heap back; and the one
  // extension below must reach well past what a run needs.
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(kThreshold));
  mallopt(M_TRIM_THRESHOLD, static_cast<int>(kThreshold * 4));
  mallopt(M_TOP_PAD, static_cast<int>(kThreshold));
  const auto before = reinterpret_cast<uintptr_t>(sbrk(0));
  void* block = std::malloc(kThreshold - kHugePage);
  const auto after = reinterpret_cast<uintptr_t>(sbrk(0));
  const uintptr_t begin = (before + kHugePage - 1) & ~(kHugePage - 1);
  const uintptr_t end = after & ~(kHugePage - 1);
  if (block != nullptr && end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
  std::free(block);
#endif
}

}  // namespace spire

#include "driver/process_memory.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>
#endif

#if !defined(SPIRE_HUGE_PAGE_HEAP)
#define SPIRE_HUGE_PAGE_HEAP 0
#endif

namespace spire {

namespace {

// Whether a mapping of the heap carries the kernel's "hg" flag (MADV_HUGEPAGE).
// After useHugePageHeap the heap is split into several mappings, each named
// [heap]; one advised mapping is enough.
bool heapAdvisedForHugePages() {
  std::ifstream smaps("/proc/self/smaps");
  bool inHeap = false;
  std::string line;
  while (std::getline(smaps, line)) {
    std::istringstream words(line);
    std::string first;
    words >> first;
    // "Key: value" lines describe the mapping whose header
    // ("start-end perms offset dev inode [name]") came last.
    if (!first.ends_with(':')) {
      inHeap = line.ends_with("[heap]");
    } else if (inHeap && first == "VmFlags:") {
      for (std::string flag; words >> flag;) {
        if (flag == "hg") return true;
      }
    }
  }
  return false;
}

}  // namespace

void useHugePageHeap() {
#if SPIRE_HUGE_PAGE_HEAP && defined(__GLIBC__) && defined(MADV_HUGEPAGE)
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

std::string describeHeap() {
  if (!SPIRE_HUGE_PAGE_HEAP) return "huge-page heap: off (built with SPIRE_HUGE_PAGE_HEAP=OFF)";
  std::error_code ignored;
  if (!std::filesystem::exists("/sys/kernel/mm/transparent_hugepage", ignored)) {
    return "huge-page heap: unavailable (the kernel has no transparent huge pages)";
  }
  if (heapAdvisedForHugePages()) return "huge-page heap: on";
  return "huge-page heap: off (no [heap] mapping in /proc/self/smaps is advised MADV_HUGEPAGE)";
}

}  // namespace spire

#include "renderer/host_allocator.h"

#include <malloc.h>

namespace spire::engine {

void stabilizeHostAllocator() {
  // Blocks up to 64 MiB come from the heap and freed memory up to 128 MiB
  // stays mapped: above any per-frame allocation of the render targets this
  // engine uses, so frame costs no longer depend on earlier frees.
  constexpr int kMmapThreshold = 64 << 20;
  constexpr int kTrimThreshold = 128 << 20;
  mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
  mallopt(M_TRIM_THRESHOLD, kTrimThreshold);
}

}  // namespace spire::engine

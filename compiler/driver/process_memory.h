// How the spirec process grows its heap. glslang builds its built-in symbol
// tables (~30 MB) in every process that makes SPIR-V; on 4 KiB pages that is
// ~7,000 page faults, a large share of a short spirec run. This is the
// in-process equivalent of GLIBC_TUNABLES=glibc.malloc.hugetlb=1, which a
// build system should not have to set.
#pragma once

namespace spire {

// Makes the main heap grow in one large step backed by transparent huge
// pages where the kernel allows them (THP "madvise" or "always"). Call once,
// first thing in main, before any thread starts; a no-op without glibc.
// Only for executables: it changes process-wide malloc settings.
void useHugePageHeap();

}  // namespace spire
